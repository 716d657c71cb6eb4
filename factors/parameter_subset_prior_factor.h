#pragma once
// ParameterSubsetPriorFactor: a Gaussian prior on some of the components of
// one parameter block, the others held. The cameras' intrinsics priors
// (PushbroomIntrinsicsPriorFactor, PinholeIntrinsicsPriorFactor) are this
// factor on their block, with the sigmas the survey states per parameter.
//
//   variable   k (vector of prior.size())
//   residual   r = k[i] - prior[i] for every i whose sigma is > 0
//              (dimension: the number of such components)
// A sigma of 0 means "held at the prior": that component has no residual
// here, and the caller keeps it constant in the solve (GraphProblemOptions::
// constant_components, heldComponents()); with every sigma 0 the factor is
// not built at all (nothing to estimate). noise() is built from the positive
// sigmas, in component order.
//
// Jacobian: analytic, the rows of the identity of the free components.

#include <memory>
#include <string>
#include <vector>

#include "core/graph/key.h"
#include "factors/ceres_factor.h"

namespace hsmap {

class ParameterSubsetPriorFactor : public CeresFactor {
 public:
  // Throws std::invalid_argument, its message starting with `name`, for
  // sizes that differ, a non-finite prior, a negative or non-finite sigma,
  // or sigmas that are all 0 (nothing to estimate).
  ParameterSubsetPriorFactor(std::string name, Key block, std::vector<double> prior,
                             const std::vector<double>& sigmas);

  std::string name() const override { return name_; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const std::vector<double>& prior() const { return prior_; }
  // Indices of the components with a sigma > 0, the residual's order.
  const std::vector<int>& freeParameters() const { return free_; }
  // Indices of the components with a sigma of 0 (to be held constant).
  static std::vector<int> heldComponents(const std::vector<double>& sigmas);

 private:
  std::string name_;
  std::vector<double> prior_;
  std::vector<int> free_;
};

}  // namespace hsmap
