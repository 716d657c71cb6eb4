#include "factors/second_difference_prior_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

SecondDifferencePriorFactor::SecondDifferencePriorFactor(Key a, Key b, Key c, NoiseModel noise)
    : CeresFactor({a, b, c}, std::move(noise), RobustLoss::none()) {
  requireNoiseDimension("SecondDifferencePriorFactor", this->noise(), kResidualDimension);
}

std::unique_ptr<ceres::CostFunction> SecondDifferencePriorFactor::createCostFunction() const {
  return std::make_unique<ceres::AutoDiffCostFunction<SecondDifferenceResidual, kResidualDimension, 1, 1, 1>>(
      new SecondDifferenceResidual{});
}

}  // namespace hsmap
