#include "factors/spline_ins_position_factor.h"

#include <ceres/autodiff_cost_function.h>

#include <cstdint>
#include <vector>

#include "core/graph/key.h"
#include "factors/factor_argument_checks.h"
#include "factors/spline_timing.h"

namespace hsmap {

namespace {

constexpr int P = SE3d::kNumParameters;

}  // namespace

SplineInsPositionFactor::SplineInsPositionFactor(const SplineTiming& spline, double t_fix,
                                                 const Eigen::Vector3d& p_W_B_measured,
                                                 const SE3d& T_B_C, NoiseModel noise,
                                                 RobustLoss robust_loss)
    : CeresFactor(activeControlPointKeys(spline.segmentAt(t_fix)), std::move(noise), robust_loss),
      t_fix_(t_fix),
      segment_(spline.segmentAt(t_fix)),
      p_W_B_measured_(p_W_B_measured),
      T_B_C_(requireRigidTransform("SplineInsPositionFactor", "T_B_C", T_B_C)) {
  requireNoiseDimension("SplineInsPositionFactor", this->noise(), kResidualDimension);
  requireFinite("SplineInsPositionFactor", "measured position", p_W_B_measured_);
}

std::unique_ptr<ceres::CostFunction> SplineInsPositionFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<SplineInsPositionResidual, kResidualDimension, P, P, P, P>>(
      new SplineInsPositionResidual{segment_.u, p_W_B_measured_, T_B_C_.inverse().t});
}

}  // namespace hsmap
