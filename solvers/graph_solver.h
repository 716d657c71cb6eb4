#pragma once
// solve(): optimise a factor graph with Ceres' Levenberg-Marquardt and write
// the optimum back into the Values.
//
// The cost minimised is sum_f 0.5 rho_f(|R_f r_f(x)|^2) over the factors f
// (R_f the square-root information of f's noise, rho_f its robust loss or
// the identity); see graph_problem.h for how the graph becomes a Ceres
// problem, solver_options.h for the presets. The Values' blocks are the
// solver's parameter blocks, so after solve() they hold the last accepted
// iterate, whatever the termination; report.usable says whether Ceres
// considers it a sound solution (it converged or ran out of iterations/time
// with a valid state).
//
// The report says, in plain words, which linear solver was used, how the cost
// went down overall and per factor type, how many factors with a robust loss
// were left beyond their loss scale (outliers), and why the solver stopped.

#include <map>
#include <set>
#include <string>

#include "core/graph/factor_graph.h"
#include "core/graph/key.h"
#include "core/graph/values.h"
#include "solvers/graph_problem.h"
#include "solvers/solver_options.h"

namespace hsmap {

struct FactorTypeReport {
  std::size_t count = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  // Robust factors whose whitened residual norm exceeds the loss scale.
  std::size_t initial_beyond_loss_scale = 0;
  std::size_t final_beyond_loss_scale = 0;
};

struct SolveReport {
  double initial_cost = 0.0;
  double final_cost = 0.0;
  // Levenberg-Marquardt iterations: accepted + rejected steps.
  int iterations = 0;
  int successful_iterations = 0;
  double wall_time_s = 0.0;
  // Where the time went (Ceres' own timers): evaluating residuals alone,
  // residuals with Jacobians, and solving the linear systems.
  double residual_evaluation_s = 0.0;
  double jacobian_evaluation_s = 0.0;
  double linear_solver_s = 0.0;
  // What Ceres actually used, e.g. "SPARSE_SCHUR (SuiteSparse)".
  std::string linear_solver;
  // "converged", "not converged", "failed" or "stopped by user".
  std::string termination;
  // Why, in plain words: "function tolerance reached",
  // "maximum number of iterations reached", ...
  std::string reason;
  // Ceres' own message, with its numbers.
  std::string ceres_message;
  bool converged = false;
  bool usable = false;

  std::size_t num_factors = 0;
  std::size_t num_variables = 0;
  std::size_t num_constant_variables = 0;
  std::size_t num_eliminated_landmarks = 0;
  int num_residuals = 0;
  int num_free_parameters = 0;  // degrees of freedom (tangent space)
  int num_threads = 0;

  std::map<std::string, FactorTypeReport> by_factor_type;

  // First line: "Levenberg–Marquardt with SPARSE_SCHUR (SuiteSparse): cost
  // 1.2e6 -> 3.4e2 in 12 iterations, 8.1 s; converged: function tolerance
  // reached", then the problem's size and where the time went, then one line
  // per factor type.
  std::string toString() const;
};

// Builds the problem (GraphProblem), solves it and returns the report.
// Throws std::invalid_argument for invalid options or an unsolvable graph
// (see GraphProblem); a solve that fails numerically is reported, not thrown.
SolveReport solve(const FactorGraph& graph, Values& values, const SolverOptions& options,
                  const std::set<Key>& constant = {});

// Solves an existing problem (e.g. with bounds, or to compute covariances on
// it afterwards).
SolveReport solve(GraphProblem& problem, const SolverOptions& options);

// A number the way the reports print it: 3 significant digits, "1.2e6" not
// "1.2e+06".
std::string formatCost(double value);

}  // namespace hsmap
