#include "factors/spline_reprojection_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <vector>

#include "factors/factor_argument_checks.h"

namespace hsmap {

namespace {

std::vector<Key> keysOf(const SplineSegment& segment, Key landmark_p_W) {
  const auto i = static_cast<std::uint64_t>(segment.first_control_point);
  return {S(i), S(i + 1), S(i + 2), S(i + 3), landmark_p_W};
}

}  // namespace

SplineReprojectionFactor::SplineReprojectionFactor(const SplineTiming& spline, double t_frame,
                                                   Key landmark_p_W, const Eigen::Vector2d& pixel,
                                                   const PinholeRadtanParameters& intrinsics,
                                                   NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor(keysOf(spline.segmentAt(t_frame), landmark_p_W), std::move(noise), robust_loss),
      t_frame_(t_frame),
      segment_(spline.segmentAt(t_frame)),
      pixel_(pixel),
      intrinsics_(PinholeRadtanCamera(intrinsics).intrinsics()) {
  requireNoiseDimension("SplineReprojectionFactor", this->noise(), kResidualDimension);
  requireFinite("SplineReprojectionFactor", "pixel", pixel_);
}

std::unique_ptr<ceres::CostFunction> SplineReprojectionFactor::createCostFunction() const {
  constexpr int P = SE3d::kNumParameters;
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplineReprojectionResidual, kResidualDimension, P, P, P, P, 3>>(
      new SplineReprojectionResidual{segment_.u, pixel_, intrinsics_});
}

}  // namespace hsmap
