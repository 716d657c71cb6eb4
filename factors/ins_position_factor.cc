#include "factors/ins_position_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

InsPositionFactor::InsPositionFactor(Key pose_T_W_C, const Eigen::Vector3d& p_W_B_measured,
                                     const SE3d& T_B_C, NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor({pose_T_W_C}, std::move(noise), robust_loss),
      p_W_B_measured_(p_W_B_measured),
      T_B_C_(requireRigidTransform("InsPositionFactor", "T_B_C", T_B_C)) {
  requireNoiseDimension("InsPositionFactor", this->noise(), kResidualDimension);
  requireFinite("InsPositionFactor", "measured position", p_W_B_measured_);
}

std::unique_ptr<ceres::CostFunction> InsPositionFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<InsPositionResidual, kResidualDimension, SE3d::kNumParameters>>(
      new InsPositionResidual{p_W_B_measured_, T_B_C_.inverse().t});
}

}  // namespace hsmap
