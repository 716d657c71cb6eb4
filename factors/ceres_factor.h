#pragma once
// CeresFactor: a Factor whose residual Ceres can evaluate.
//
// Every concrete factor in factors/ derives from it and returns its *raw*
// (un-whitened) residual r(x) as a ceres::CostFunction whose parameter blocks
// are the variables of keys(), in that order, with the layouts of
// core/graph/values.h (a pose is [qx qy qz qw tx ty tz]). The solver whitens
// the residual with the factor's NoiseModel (R r, R J) and applies its
// RobustLoss, so a factor only says what it measures, as GTSAM's factors do.

#include <ceres/cost_function.h>

#include <memory>

#include "core/graph/factor.h"

namespace hsmap {

class CeresFactor : public Factor {
 public:
  // A new cost function for this factor; the caller (the solver) owns it.
  virtual std::unique_ptr<ceres::CostFunction> createCostFunction() const = 0;

 protected:
  using Factor::Factor;
};

}  // namespace hsmap
