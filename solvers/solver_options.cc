#include "solvers/solver_options.h"

#include "core/util/thread_budget.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace hsmap {

namespace {

[[noreturn]] void invalid(const std::string& field, double value, const std::string& expected) {
  std::ostringstream message;
  message << "SolverOptions." << field << " must be " << expected << ", got " << value;
  throw std::invalid_argument(message.str());
}

void checkTolerance(const std::string& field, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) invalid(field, value, "a finite number >= 0");
}

}  // namespace

void SolverOptions::validate() const {
  if (max_iterations <= 0) invalid("max_iterations", max_iterations, "> 0");
  checkTolerance("function_tolerance", function_tolerance);
  checkTolerance("gradient_tolerance", gradient_tolerance);
  checkTolerance("parameter_tolerance", parameter_tolerance);
  if (!(max_time_s > 0.0)) invalid("max_time_s", max_time_s, "> 0 seconds");
  if (num_threads < 0) invalid("num_threads", num_threads, ">= 0 (0 = every hardware thread)");
  switch (linear_solver) {
    case LinearSolver::sparse_schur:
    case LinearSolver::iterative_schur:
    case LinearSolver::sparse_normal_cholesky:
    case LinearSolver::dense_schur:
      break;
    default:
      invalid("linear_solver", static_cast<int>(linear_solver),
              "one of sparse_schur, iterative_schur, sparse_normal_cholesky, dense_schur");
  }
}

int SolverOptions::resolvedNumThreads() const {
  if (num_threads > 0) return num_threads;
  return threadBudget();
}

ceres::Solver::Options SolverOptions::toCeres() const {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  switch (linear_solver) {
    case LinearSolver::sparse_schur:
      options.linear_solver_type = ceres::SPARSE_SCHUR;
      options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
      break;
    case LinearSolver::iterative_schur:
      options.linear_solver_type = ceres::ITERATIVE_SCHUR;
      options.preconditioner_type = ceres::SCHUR_JACOBI;
      break;
    case LinearSolver::sparse_normal_cholesky:
      options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
      break;
    case LinearSolver::dense_schur:
      options.linear_solver_type = ceres::DENSE_SCHUR;
      options.dense_linear_algebra_library_type = ceres::EIGEN;
      break;
  }
  options.max_num_iterations = max_iterations;
  options.function_tolerance = function_tolerance;
  options.gradient_tolerance = gradient_tolerance;
  options.parameter_tolerance = parameter_tolerance;
  options.max_solver_time_in_seconds = max_time_s;
  options.num_threads = resolvedNumThreads();
  // Progress goes through hsmap's own iteration callback (graph_solver.cc),
  // not through glog.
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

const char* toString(SolverOptions::LinearSolver solver) {
  switch (solver) {
    case SolverOptions::LinearSolver::sparse_schur: return "sparse_schur";
    case SolverOptions::LinearSolver::iterative_schur: return "iterative_schur";
    case SolverOptions::LinearSolver::sparse_normal_cholesky: return "sparse_normal_cholesky";
    case SolverOptions::LinearSolver::dense_schur: return "dense_schur";
  }
  return "?";
}

SolverOptions::LinearSolver parseLinearSolver(const std::string& name) {
  for (const auto solver : {SolverOptions::LinearSolver::sparse_schur,
                            SolverOptions::LinearSolver::iterative_schur,
                            SolverOptions::LinearSolver::sparse_normal_cholesky,
                            SolverOptions::LinearSolver::dense_schur}) {
    if (name == toString(solver)) return solver;
  }
  throw std::invalid_argument(
      "unknown linear solver \"" + name +
      "\": expected sparse_schur, iterative_schur, sparse_normal_cholesky or dense_schur");
}

}  // namespace hsmap
