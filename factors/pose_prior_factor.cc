#include "factors/pose_prior_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

PosePriorFactor::PosePriorFactor(Key pose, const SE3d& prior, NoiseModel noise,
                                 RobustLoss robust_loss)
    : CeresFactor({pose}, std::move(noise), robust_loss),
      prior_(requireRigidTransform("PosePriorFactor", "prior", prior)) {
  requireNoiseDimension("PosePriorFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> PosePriorFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<PosePriorResidual, kResidualDimension, SE3d::kNumParameters>>(
      new PosePriorResidual{prior_.inverse()});
}

}  // namespace hsmap
