#include "solvers/graph_solver.h"

#include <ceres/iteration_callback.h>
#include <ceres/solver.h>
#include <ceres/types.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace hsmap {

namespace {

// One line per Levenberg-Marquardt iteration, for SolverOptions::verbose.
class ProgressCallback final : public ceres::IterationCallback {
 public:
  explicit ProgressCallback(std::ostream& stream) : stream_(stream) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    stream_ << "iteration " << summary.iteration << ": cost " << formatCost(summary.cost);
    if (summary.iteration > 0) {
      stream_ << ", change " << formatCost(-summary.cost_change)
              << (summary.step_is_successful ? "" : " (step rejected)");
    }
    char time[32];
    std::snprintf(time, sizeof(time), "%.2f", summary.cumulative_time_in_seconds);
    stream_ << ", trust region radius " << formatCost(summary.trust_region_radius) << ", " << time
            << " s" << std::endl;
    return ceres::SOLVER_CONTINUE;
  }

 private:
  std::ostream& stream_;
};

std::string describeLinearSolver(const ceres::Solver::Summary& summary) {
  std::string text = ceres::LinearSolverTypeToString(summary.linear_solver_type_used);
  switch (summary.linear_solver_type_used) {
    case ceres::SPARSE_SCHUR:
    case ceres::SPARSE_NORMAL_CHOLESKY:
      switch (summary.sparse_linear_algebra_library_type) {
        case ceres::SUITE_SPARSE: return text + " (SuiteSparse)";
        case ceres::EIGEN_SPARSE: return text + " (Eigen)";
        default:
          return text + " (" +
                 ceres::SparseLinearAlgebraLibraryTypeToString(
                     summary.sparse_linear_algebra_library_type) +
                 ")";
      }
    case ceres::DENSE_SCHUR:
    case ceres::DENSE_QR:
    case ceres::DENSE_NORMAL_CHOLESKY:
      switch (summary.dense_linear_algebra_library_type) {
        case ceres::EIGEN: return text + " (Eigen)";
        default:
          return text + " (" +
                 ceres::DenseLinearAlgebraLibraryTypeToString(
                     summary.dense_linear_algebra_library_type) +
                 ")";
      }
    case ceres::ITERATIVE_SCHUR:
    case ceres::CGNR:
      return text + " (" + ceres::PreconditionerTypeToString(summary.preconditioner_type_used) +
             " preconditioner)";
    default:
      return text;
  }
}

std::string describeTermination(ceres::TerminationType type) {
  switch (type) {
    case ceres::CONVERGENCE: return "converged";
    case ceres::NO_CONVERGENCE: return "not converged";
    case ceres::FAILURE: return "failed";
    case ceres::USER_SUCCESS: return "stopped by user (success)";
    case ceres::USER_FAILURE: return "stopped by user (failure)";
  }
  return "unknown termination";
}

// "Function tolerance reached. |cost_change|/cost: ..." -> "function
// tolerance reached": Ceres' first sentence, without its numbers.
std::string plainReason(const std::string& message) {
  std::string reason = message;
  const std::size_t end = reason.find(". ");
  if (end != std::string::npos) reason.resize(end);
  while (!reason.empty() && (reason.back() == '.' || reason.back() == ' ')) reason.pop_back();
  if (!reason.empty() && std::isupper(static_cast<unsigned char>(reason[0])) &&
      !(reason.size() > 1 && std::isupper(static_cast<unsigned char>(reason[1])))) {
    reason[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(reason[0])));
  }
  return reason.empty() ? "no reason given" : reason;
}

}  // namespace

std::string formatCost(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.3g", value);
  // Drop the exponent's "+" and leading zeros: 1.2e+06 -> 1.2e6, 3e-05 -> 3e-5.
  std::string text(buffer);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e);
  std::string exponent = text.substr(e + 1);
  std::string sign;
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) {
    if (exponent[0] == '-') sign = "-";
    exponent.erase(0, 1);
  }
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return mantissa + "e" + sign + exponent;
}

std::string SolveReport::toString() const {
  std::ostringstream text;
  char time[32];
  std::snprintf(time, sizeof(time), "%.1f", wall_time_s);
  text << "Levenberg–Marquardt with " << linear_solver << ": cost " << formatCost(initial_cost)
       << " -> " << formatCost(final_cost) << " in " << iterations
       << (iterations == 1 ? " iteration, " : " iterations, ") << time << " s; " << termination
       << ": " << reason;
  text << "\n  " << num_factors << " factors, " << num_variables << " variables ("
       << num_constant_variables << " constant, " << num_eliminated_landmarks
       << " landmarks eliminated), " << num_free_parameters << " degrees of freedom, "
       << num_threads << (num_threads == 1 ? " thread" : " threads");
  char timings[96];
  std::snprintf(timings, sizeof(timings), "; %.1f s evaluating Jacobians, %.1f s in the linear solver",
                jacobian_evaluation_s, linear_solver_s);
  text << timings;
  for (const auto& [name, entry] : by_factor_type) {
    text << "\n  " << name << ": " << entry.count << (entry.count == 1 ? " factor" : " factors")
         << ", cost " << formatCost(entry.initial_cost) << " -> " << formatCost(entry.final_cost);
    if (entry.initial_beyond_loss_scale > 0 || entry.final_beyond_loss_scale > 0) {
      text << ", beyond the robust loss scale " << entry.initial_beyond_loss_scale << " -> "
           << entry.final_beyond_loss_scale;
    }
  }
  return text.str();
}

SolveReport solve(const FactorGraph& graph, Values& values, const SolverOptions& options,
                  const std::set<Key>& constant) {
  options.validate();
  GraphProblemOptions problem_options;
  problem_options.constant = constant;
  GraphProblem problem(graph, values, problem_options);
  return solve(problem, options);
}

SolveReport solve(GraphProblem& problem, const SolverOptions& options) {
  options.validate();
  ceres::Solver::Options ceres_options = options.toCeres();
  if (options.linear_solver != SolverOptions::LinearSolver::sparse_normal_cholesky) {
    ceres_options.linear_solver_ordering = problem.schurOrdering();
  }
  ProgressCallback progress(options.progress_stream != nullptr ? *options.progress_stream
                                                               : std::cerr);
  if (options.verbose) ceres_options.callbacks.push_back(&progress);

  SolveReport report;
  report.num_threads = ceres_options.num_threads;
  const std::map<std::string, FactorTypeCost> before =
      problem.costByFactorType(ceres_options.num_threads);

  ceres::Solver::Summary summary;
  const auto start = std::chrono::steady_clock::now();
  problem.loadValues();
  ceres::Solve(ceres_options, &problem.problem(), &summary);
  problem.storeValues();
  report.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::map<std::string, FactorTypeCost> after =
      problem.costByFactorType(ceres_options.num_threads);

  report.residual_evaluation_s = summary.residual_evaluation_time_in_seconds;
  report.jacobian_evaluation_s = summary.jacobian_evaluation_time_in_seconds;
  report.linear_solver_s = summary.linear_solver_time_in_seconds;
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  // summary.iterations[0] is the initial state (Ceres counts it as a
  // successful step); the iterations proper follow it.
  report.iterations =
      summary.iterations.empty() ? 0 : static_cast<int>(summary.iterations.size()) - 1;
  for (std::size_t i = 1; i < summary.iterations.size(); ++i) {
    if (summary.iterations[i].step_is_successful) ++report.successful_iterations;
  }
  report.linear_solver = describeLinearSolver(summary);
  report.termination = describeTermination(summary.termination_type);
  report.reason = plainReason(summary.message);
  report.ceres_message = summary.message;
  report.converged = summary.termination_type == ceres::CONVERGENCE;
  report.usable = summary.IsSolutionUsable();

  report.num_factors = problem.graph().size();
  report.num_variables = problem.variables().size();
  report.num_constant_variables = problem.numConstantVariables();
  report.num_eliminated_landmarks = problem.numEliminatedLandmarks();
  report.num_residuals = summary.num_residuals;
  report.num_free_parameters = problem.numFreeParameters();

  for (const auto& [name, cost] : before) {
    FactorTypeReport& entry = report.by_factor_type[name];
    entry.count = cost.count;
    entry.initial_cost = cost.cost;
    entry.initial_beyond_loss_scale = cost.beyond_loss_scale;
  }
  for (const auto& [name, cost] : after) {
    FactorTypeReport& entry = report.by_factor_type[name];
    entry.final_cost = cost.cost;
    entry.final_beyond_loss_scale = cost.beyond_loss_scale;
  }
  // A failed preprocessing (e.g. infeasible bounds) leaves Ceres' costs unset;
  // report the evaluated ones instead, so the numbers always mean something.
  if (summary.termination_type == ceres::FAILURE && summary.num_successful_steps == 0) {
    report.initial_cost = 0.0;
    for (const auto& [name, cost] : before) report.initial_cost += cost.cost;
    report.final_cost = report.initial_cost;
  }
  return report;
}

}  // namespace hsmap
