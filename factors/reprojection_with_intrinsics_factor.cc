#include "factors/reprojection_with_intrinsics_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

ReprojectionWithIntrinsicsFactor::ReprojectionWithIntrinsicsFactor(Key pose_T_W_C,
                                                                   Key landmark_p_W,
                                                                   Key intrinsics,
                                                                   const Eigen::Vector2d& pixel,
                                                                   NoiseModel noise,
                                                                   RobustLoss robust_loss)
    : CeresFactor({pose_T_W_C, landmark_p_W, intrinsics}, std::move(noise), robust_loss),
      pixel_(pixel) {
  requireNoiseDimension("ReprojectionWithIntrinsicsFactor", this->noise(), kResidualDimension);
  requireFinite("ReprojectionWithIntrinsicsFactor", "pixel", pixel_);
}

std::unique_ptr<ceres::CostFunction> ReprojectionWithIntrinsicsFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<ReprojectionWithIntrinsicsResidual, kResidualDimension,
                                  SE3d::kNumParameters, 3, PinholeRadtanCamera::kNumIntrinsics>>(
      new ReprojectionWithIntrinsicsResidual{pixel_});
}

}  // namespace hsmap
