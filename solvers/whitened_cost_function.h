#pragma once
// WhitenedCostFunction: a factor's raw residual r(x) (CeresFactor::
// createCostFunction(), factors/ceres_factor.h) seen through its noise model.
//
// With the square-root information R of the NoiseModel (R^T R = Sigma^-1),
// the solver minimises 0.5 |R r(x)|^2 (then through the robust loss), so this
// wrapper returns the whitened residual R r and the whitened Jacobians R J_k
// of every parameter block k. When R is diagonal (independent components, the
// common case: pixels, INS fixes) whitening is a per-row scale and no matrix
// product is formed.
//
// The wrapper owns the raw cost function and copies R; it keeps the raw
// function's parameter block sizes and residual count, and passes on a
// failed evaluation (false) unchanged. Jacobian blocks Ceres does not ask for
// (nullptr, e.g. constant variables) are left alone.

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <memory>

#include "core/graph/noise_model.h"

namespace hsmap {

class WhitenedCostFunction final : public ceres::CostFunction {
 public:
  // Throws std::invalid_argument when the raw residual count differs from the
  // noise model's dimension, or `raw` is null.
  WhitenedCostFunction(std::unique_ptr<ceres::CostFunction> raw, const NoiseModel& noise);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  const ceres::CostFunction& raw() const { return *raw_; }

 private:
  std::unique_ptr<ceres::CostFunction> raw_;
  bool diagonal_;
  Eigen::VectorXd diagonal_sqrt_information_;  // used when diagonal_
  Eigen::MatrixXd sqrt_information_;           // used otherwise
};

}  // namespace hsmap
