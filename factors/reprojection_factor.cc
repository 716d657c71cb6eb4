#include "factors/reprojection_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

ReprojectionFactor::ReprojectionFactor(Key pose_T_W_C, Key landmark_p_W,
                                       const Eigen::Vector2d& pixel,
                                       const PinholeRadtanParameters& intrinsics, NoiseModel noise,
                                       RobustLoss robust_loss)
    : CeresFactor({pose_T_W_C, landmark_p_W}, std::move(noise), robust_loss),
      pixel_(pixel),
      intrinsics_(PinholeRadtanCamera(intrinsics).intrinsics()) {
  requireNoiseDimension("ReprojectionFactor", this->noise(), kResidualDimension);
  requireFinite("ReprojectionFactor", "pixel", pixel_);
}

std::unique_ptr<ceres::CostFunction> ReprojectionFactor::createCostFunction() const {
  return std::make_unique<ceres::AutoDiffCostFunction<ReprojectionResidual, kResidualDimension,
                                                      SE3d::kNumParameters, 3>>(
      new ReprojectionResidual{pixel_, intrinsics_});
}

}  // namespace hsmap
