#pragma once
// GaussianPriorFactor: a Gaussian prior on a Euclidean variable (scalar,
// vector or point): what is known of it before the data, e.g. the water's
// attenuation from pure water's absorption, or a flat lamp beam.
//
//   variable   x (n doubles, as stored: Values' scalar, vector or point3)
//   residual   r = x − prior                               (n)
//   Jacobian   the identity (analytic)
// The noise model (n-dimensional) holds the prior's 1-sigma.

#include <Eigen/Core>
#include <memory>
#include <string>

#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

class GaussianPriorFactor : public CeresFactor {
 public:
  // Throws std::invalid_argument for an empty or non-finite prior, or a noise
  // model whose dimension is not the prior's.
  GaussianPriorFactor(Key variable, Eigen::VectorXd prior, NoiseModel noise);

  std::string name() const override { return "GaussianPriorFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const Eigen::VectorXd& prior() const { return prior_; }

 private:
  Eigen::VectorXd prior_;
};

}  // namespace hsmap
