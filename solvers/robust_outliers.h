#pragma once
// Which factors ended as outliers: the factors with a robust loss whose
// whitened residual norm |R r| exceeds the loss scale c (in sigmas, see
// core/graph/noise_model.h) at the given values. These are the factors the
// solver down-weighted: a Huber loss is linear beyond c, a Cauchy loss
// flattens out. The front-end calls this after each local bundle adjustment
// and removes the matching observations from its map, so that the next
// window starts without them.
//
// The test is exactly the one behind SolveReport's beyond_loss_scale counts
// (GraphProblem::evaluateFactors()), so the indices returned after a solve
// are as many as the report's final_beyond_loss_scale summed over the
// factor types. Factors without a robust loss are never listed, however
// large their residual (INS and priors are not outlier-tested).
//
// Expect inliers there too: for a 2-D residual with Gaussian noise a
// fraction exp(-c^2 / 2) of the inliers lies beyond c (1.1 % for c = 3), so
// choose c (or test the listed factors again) with that in mind.

#include <cstddef>
#include <vector>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "solvers/graph_problem.h"

namespace hsmap {

// Indices into `graph` (graph order, increasing) of the robust factors
// beyond their loss scale at `values`. The values are not changed: the
// residuals are evaluated on a copy, through a GraphProblem built for it
// (one problem build and one evaluation on `num_threads` threads).
// Throws what GraphProblem throws for a graph that cannot be evaluated
// (std::invalid_argument: a key without a value, a factor that is not a
// CeresFactor, ...), std::runtime_error when a factor fails to evaluate.
std::vector<std::size_t> factorsBeyondLossScale(const FactorGraph& graph, const Values& values,
                                                int num_threads = 1);

// The same on a problem already built (e.g. the one just solved), at its
// current values.
std::vector<std::size_t> factorsBeyondLossScale(const GraphProblem& problem, int num_threads = 1);

}  // namespace hsmap
