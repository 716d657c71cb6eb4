#include "factors/time_offset_prior_factor.h"

#include <ceres/autodiff_cost_function.h>

#include "factors/factor_argument_checks.h"

namespace hsmap {

TimeOffsetPriorFactor::TimeOffsetPriorFactor(Key time_offset_d, double prior_s, NoiseModel noise)
    : CeresFactor({time_offset_d}, std::move(noise), RobustLoss::none()), prior_s_(prior_s) {
  requireNoiseDimension("TimeOffsetPriorFactor", this->noise(), kResidualDimension);
  requireFinite("TimeOffsetPriorFactor", "prior", prior_s_);
}

std::unique_ptr<ceres::CostFunction> TimeOffsetPriorFactor::createCostFunction() const {
  return std::make_unique<
      ceres::AutoDiffCostFunction<TimeOffsetPriorResidual, kResidualDimension, 1>>(
      new TimeOffsetPriorResidual{prior_s_});
}

}  // namespace hsmap
