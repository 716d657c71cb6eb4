#include "factors/between_pose_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

BetweenPoseFactor::BetweenPoseFactor(Key pose_T_W_A, Key pose_T_W_B, const SE3d& T_A_B_measured,
                                     NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor({pose_T_W_A, pose_T_W_B}, std::move(noise), robust_loss),
      T_A_B_measured_(requireRigidTransform("BetweenPoseFactor", "measured T_A_B", T_A_B_measured)) {
  requireNoiseDimension("BetweenPoseFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> BetweenPoseFactor::createCostFunction() const {
  return std::make_unique<ceres::AutoDiffCostFunction<BetweenPoseResidual, kResidualDimension,
                                                      SE3d::kNumParameters, SE3d::kNumParameters>>(
      new BetweenPoseResidual{T_A_B_measured_.inverse()});
}

}  // namespace hsmap
