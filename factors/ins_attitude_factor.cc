#include "factors/ins_attitude_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

InsAttitudeFactor::InsAttitudeFactor(Key pose_T_W_C, const Eigen::Quaterniond& q_W_B_measured,
                                     const SE3d& T_B_C, NoiseModel noise, RobustLoss robust_loss)
    : CeresFactor({pose_T_W_C}, std::move(noise), robust_loss),
      q_W_B_measured_(requireUnitQuaternion("InsAttitudeFactor", "measured attitude q_W_B",
                                            q_W_B_measured)),
      T_B_C_(requireRigidTransform("InsAttitudeFactor", "T_B_C", T_B_C)) {
  requireNoiseDimension("InsAttitudeFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> InsAttitudeFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<InsAttitudeResidual, kResidualDimension, SE3d::kNumParameters>>(
      new InsAttitudeResidual{q_W_B_measured_.conjugate(), T_B_C_.q.conjugate()});
}

}  // namespace hsmap
