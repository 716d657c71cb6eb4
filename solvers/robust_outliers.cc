#include "solvers/robust_outliers.h"

namespace hsmap {

std::vector<std::size_t> factorsBeyondLossScale(const GraphProblem& problem, int num_threads) {
  const std::vector<FactorEvaluation> evaluations = problem.evaluateFactors(num_threads);
  std::vector<std::size_t> beyond;
  for (std::size_t index = 0; index < evaluations.size(); ++index) {
    if (evaluations[index].beyond_loss_scale) beyond.push_back(index);
  }
  return beyond;
}

std::vector<std::size_t> factorsBeyondLossScale(const FactorGraph& graph, const Values& values,
                                                int num_threads) {
  // A GraphProblem holds its Values' blocks as mutable parameter blocks; a
  // copy keeps the caller's values untouched by construction.
  Values copy = values;
  const GraphProblem problem(graph, copy);
  return factorsBeyondLossScale(problem, num_threads);
}

}  // namespace hsmap
