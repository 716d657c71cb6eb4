// SolverOptions: documented defaults, validate() messages, the Ceres mapping
// of each preset, names.

#include "solvers/solver_options.h"

#include <gtest/gtest.h>

#include <limits>
#include <thread>

namespace hsmap {
namespace {

std::string validationError(const SolverOptions& options) {
  try {
    options.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "valid";
}

TEST(SolverOptions, DefaultsAreSparseSchurLevenbergMarquardtOnEveryThread) {
  const SolverOptions options;
  EXPECT_EQ(options.linear_solver, SolverOptions::LinearSolver::sparse_schur);
  EXPECT_EQ(options.max_iterations, 100);
  EXPECT_EQ(options.function_tolerance, 1e-6);
  EXPECT_EQ(options.gradient_tolerance, 1e-10);
  EXPECT_EQ(options.parameter_tolerance, 1e-8);
  EXPECT_EQ(options.num_threads, 0);
  EXPECT_FALSE(options.verbose);
  EXPECT_EQ(validationError(options), "valid");

  const ceres::Solver::Options ceres_options = options.toCeres();
  EXPECT_EQ(ceres_options.minimizer_type, ceres::TRUST_REGION);
  EXPECT_EQ(ceres_options.trust_region_strategy_type, ceres::LEVENBERG_MARQUARDT);
  EXPECT_EQ(ceres_options.linear_solver_type, ceres::SPARSE_SCHUR);
  EXPECT_EQ(ceres_options.sparse_linear_algebra_library_type, ceres::SUITE_SPARSE);
  EXPECT_EQ(ceres_options.max_num_iterations, 100);
  const int hardware = std::max(1u, std::thread::hardware_concurrency());
  EXPECT_EQ(ceres_options.num_threads, hardware);
  EXPECT_EQ(ceres_options.logging_type, ceres::SILENT);
  std::string why;
  EXPECT_TRUE(ceres_options.IsValid(&why)) << why;
}

TEST(SolverOptions, PresetsMapToTheirCeresLinearSolvers) {
  SolverOptions options;
  options.num_threads = 3;
  options.linear_solver = SolverOptions::LinearSolver::iterative_schur;
  ceres::Solver::Options ceres_options = options.toCeres();
  EXPECT_EQ(ceres_options.linear_solver_type, ceres::ITERATIVE_SCHUR);
  EXPECT_EQ(ceres_options.preconditioner_type, ceres::SCHUR_JACOBI);
  EXPECT_EQ(ceres_options.num_threads, 3);
  std::string why;
  EXPECT_TRUE(ceres_options.IsValid(&why)) << why;

  options.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  ceres_options = options.toCeres();
  EXPECT_EQ(ceres_options.linear_solver_type, ceres::SPARSE_NORMAL_CHOLESKY);
  EXPECT_EQ(ceres_options.sparse_linear_algebra_library_type, ceres::SUITE_SPARSE);
  EXPECT_TRUE(ceres_options.IsValid(&why)) << why;

  options.linear_solver = SolverOptions::LinearSolver::dense_schur;
  ceres_options = options.toCeres();
  EXPECT_EQ(ceres_options.linear_solver_type, ceres::DENSE_SCHUR);
  EXPECT_EQ(ceres_options.dense_linear_algebra_library_type, ceres::EIGEN);
  EXPECT_TRUE(ceres_options.IsValid(&why)) << why;
}

TEST(SolverOptions, ValidateNamesTheFieldTheValueAndWhatIsAllowed) {
  SolverOptions options;
  options.max_iterations = 0;
  EXPECT_EQ(validationError(options), "SolverOptions.max_iterations must be > 0, got 0");
  options = {};
  options.function_tolerance = -1e-3;
  EXPECT_EQ(validationError(options),
            "SolverOptions.function_tolerance must be a finite number >= 0, got -0.001");
  options = {};
  options.gradient_tolerance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validationError(options),
            "SolverOptions.gradient_tolerance must be a finite number >= 0, got nan");
  options = {};
  options.parameter_tolerance = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validationError(options),
            "SolverOptions.parameter_tolerance must be a finite number >= 0, got inf");
  options = {};
  options.max_time_s = 0.0;
  EXPECT_EQ(validationError(options), "SolverOptions.max_time_s must be > 0 seconds, got 0");
  options = {};
  options.num_threads = -2;
  EXPECT_EQ(validationError(options),
            "SolverOptions.num_threads must be >= 0 (0 = every hardware thread), got -2");
}

TEST(SolverOptions, LinearSolverNamesRoundTrip) {
  for (const auto solver : {SolverOptions::LinearSolver::sparse_schur,
                            SolverOptions::LinearSolver::iterative_schur,
                            SolverOptions::LinearSolver::sparse_normal_cholesky,
                            SolverOptions::LinearSolver::dense_schur}) {
    EXPECT_EQ(parseLinearSolver(toString(solver)), solver);
  }
  EXPECT_STREQ(toString(SolverOptions::LinearSolver::dense_schur), "dense_schur");
  try {
    parseLinearSolver("dense_qr");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "unknown linear solver \"dense_qr\": expected sparse_schur, iterative_schur, "
                 "sparse_normal_cholesky or dense_schur");
  }
}

}  // namespace
}  // namespace hsmap
