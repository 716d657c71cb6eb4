// solve(): recovery of closed-form optima with every linear-solver preset,
// the SE(3) manifold inside a real solve, constants, and the report.

#include "solvers/graph_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <regex>
#include <sstream>

#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using test::LinearFactor;

// A linear least-squares problem shaped like bundle adjustment: 3 "cameras"
// K(j) (3-vectors) and 30 "landmarks" L(i) (3-vectors), every landmark
// measured by every camera through random 2x3 blocks, plus a prior on each
// camera. Its optimum is the solution of the normal equations.
struct LinearProblem {
  FactorGraph graph;
  Values initial;
  std::vector<Key> keys;  // unknown order of the dense solution
  Eigen::VectorXd optimum;
  double optimal_cost = 0.0;
  double initial_cost = 0.0;

  explicit LinearProblem(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    auto random = [&](int rows, int cols) {
      Eigen::MatrixXd m(rows, cols);
      for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) m(i, j) = normal(rng);
      return m;
    };
    for (int j = 0; j < 3; ++j) keys.push_back(K(j));
    for (int i = 0; i < 30; ++i) keys.push_back(L(i));
    std::map<Key, int> column;
    for (std::size_t k = 0; k < keys.size(); ++k) column[keys[k]] = static_cast<int>(3 * k);
    const int n = static_cast<int>(3 * keys.size());

    Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    std::vector<std::shared_ptr<const LinearFactor>> factors;
    for (int j = 0; j < 3; ++j) {
      factors.push_back(std::make_shared<LinearFactor>(
          std::vector<Key>{K(j)}, std::vector<Eigen::MatrixXd>{Eigen::MatrixXd::Identity(3, 3)},
          random(3, 1), NoiseModel::isotropic(3, 0.5)));
      for (int i = 0; i < 30; ++i) {
        const Eigen::VectorXd sigmas = (random(2, 1).array().abs() + 0.2).matrix();
        factors.push_back(std::make_shared<LinearFactor>(
            std::vector<Key>{K(j), L(i)}, std::vector<Eigen::MatrixXd>{random(2, 3), random(2, 3)},
            random(2, 1), NoiseModel::fromSigmas(sigmas)));
      }
    }
    for (const auto& factor : factors) {
      graph.add(factor);
      // Whitened rows of this factor in the dense system.
      const Eigen::MatrixXd& R = factor->noise().sqrtInformation();
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(factor->residualDimension(), n);
      for (std::size_t k = 0; k < factor->keys().size(); ++k) {
        J.middleCols(column[factor->keys()[k]], 3) = factor->A()[k];
      }
      const Eigen::MatrixXd RJ = R * J;
      information += RJ.transpose() * RJ;
      rhs += RJ.transpose() * (R * factor->b());
    }
    optimum = information.ldlt().solve(rhs);
    Eigen::VectorXd start(n);
    for (int i = 0; i < n; ++i) start[i] = 3.0 * normal(rng);
    for (const Key& key : keys) initial.insertVector(key, start.segment(column[key], 3));
    auto cost = [&](const Eigen::VectorXd& x) {
      double total = 0.0;
      for (const auto& factor : factors) {
        Eigen::VectorXd r = -factor->b();
        for (std::size_t k = 0; k < factor->keys().size(); ++k) {
          r += factor->A()[k] * x.segment(column[factor->keys()[k]], 3);
        }
        total += 0.5 * (factor->noise().sqrtInformation() * r).squaredNorm();
      }
      return total;
    };
    optimal_cost = cost(optimum);
    initial_cost = cost(start);
  }

  Eigen::VectorXd stack(const Values& values) const {
    Eigen::VectorXd x(3 * keys.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
      x.segment<3>(3 * k) = Eigen::Map<const Eigen::Vector3d>(values.data(keys[k]));
    }
    return x;
  }
};

SolverOptions tightOptions(SolverOptions::LinearSolver solver) {
  SolverOptions options;
  options.linear_solver = solver;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-15;
  options.parameter_tolerance = 1e-15;
  options.max_iterations = 50;
  options.num_threads = 2;
  return options;
}

class GraphSolverPresetTest
    : public ::testing::TestWithParam<std::pair<SolverOptions::LinearSolver, std::string>> {};

TEST_P(GraphSolverPresetTest, RecoversTheLeastSquaresOptimumOfALinearProblem) {
  const auto& [solver, description] = GetParam();
  LinearProblem linear(5);
  Values values = linear.initial;
  const SolveReport report = solve(linear.graph, values, tightOptions(solver));
  EXPECT_TRUE(report.usable);
  EXPECT_EQ(report.linear_solver, description);
  EXPECT_LT((linear.stack(values) - linear.optimum).lpNorm<Eigen::Infinity>(), 1e-6)
      << report.toString();
  EXPECT_NEAR(report.initial_cost, linear.initial_cost, 1e-9 * linear.initial_cost);
  EXPECT_NEAR(report.final_cost, linear.optimal_cost, 1e-8 * linear.optimal_cost);
  EXPECT_EQ(report.num_factors, 93u);
  EXPECT_EQ(report.num_variables, 33u);
  EXPECT_EQ(report.num_free_parameters, 99);
  EXPECT_EQ(report.num_residuals, 3 * 3 + 90 * 2);
  ASSERT_EQ(report.by_factor_type.size(), 1u);
  const FactorTypeReport& entry = report.by_factor_type.at("LinearFactor");
  EXPECT_EQ(entry.count, 93u);
  EXPECT_NEAR(entry.initial_cost, linear.initial_cost, 1e-9 * linear.initial_cost);
  EXPECT_NEAR(entry.final_cost, linear.optimal_cost, 1e-8 * linear.optimal_cost);
}

INSTANTIATE_TEST_SUITE_P(
    Presets, GraphSolverPresetTest,
    ::testing::Values(
        std::make_pair(SolverOptions::LinearSolver::sparse_schur, "SPARSE_SCHUR (SuiteSparse)"),
        std::make_pair(SolverOptions::LinearSolver::iterative_schur,
                       "ITERATIVE_SCHUR (SCHUR_JACOBI preconditioner)"),
        std::make_pair(SolverOptions::LinearSolver::sparse_normal_cholesky,
                       "SPARSE_NORMAL_CHOLESKY (SuiteSparse)"),
        std::make_pair(SolverOptions::LinearSolver::dense_schur, "DENSE_SCHUR (Eigen)")));

// 10 poses along a chain: a prior on x0 and relative measurements, all exact.
struct PoseChain {
  FactorGraph graph;
  std::vector<SE3d> truth;
  Values initial;
  explicit PoseChain(unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int i = 0; i < 10; ++i) truth.push_back(test::randomPose(rng, 5.0));
    graph.emplace<test::TestPosePriorFactor>(X(0), truth[0], NoiseModel::isotropic(6, 0.01));
    for (int i = 0; i + 1 < 10; ++i) {
      graph.emplace<test::TestBetweenFactor>(X(i), X(i + 1), truth[i].inverse() * truth[i + 1],
                                             NoiseModel::isotropic(6, 0.1));
    }
    for (int i = 0; i < 10; ++i) {
      Vector6d xi;
      for (int k = 0; k < 6; ++k) xi[k] = 0.2 * normal(rng);
      const SE3d start = truth[i] * SE3d::exp(xi);
      initial.insertPose(X(i), start.q, start.t);
    }
  }
  double maxError(const Values& values) const {
    double worst = 0.0;
    for (int i = 0; i < 10; ++i) {
      const SE3d estimate(values.poseRotation(X(i)), values.poseTranslation(X(i)));
      worst = std::max(worst, (truth[i].inverse() * estimate).log().norm());
    }
    return worst;
  }
};

TEST(GraphSolver, RecoversAPoseChainThroughTheSe3Manifold) {
  for (const auto solver : {SolverOptions::LinearSolver::sparse_schur,
                            SolverOptions::LinearSolver::sparse_normal_cholesky,
                            SolverOptions::LinearSolver::dense_schur}) {
    PoseChain chain(21);
    Values values = chain.initial;
    ASSERT_GT(chain.maxError(values), 0.1);
    const SolveReport report = solve(chain.graph, values, tightOptions(solver));
    EXPECT_TRUE(report.converged) << report.toString();
    EXPECT_LT(chain.maxError(values), 1e-9) << report.toString();
    EXPECT_LT(report.final_cost, 1e-18);
    // Poses stay unit quaternions.
    for (int i = 0; i < 10; ++i) EXPECT_NEAR(values.poseRotation(X(i)).norm(), 1.0, 1e-14);
  }
}

TEST(GraphSolver, ConstantVariablesAreNotMoved) {
  PoseChain chain(23);
  Values values = chain.initial;
  const Eigen::Quaterniond q0 = values.poseRotation(X(3));
  const Eigen::Vector3d t0 = values.poseTranslation(X(3));
  const SolveReport report = solve(chain.graph, values, tightOptions(SolverOptions::LinearSolver::sparse_schur), {X(3)});
  EXPECT_TRUE(report.usable);
  EXPECT_EQ(values.poseRotation(X(3)).coeffs(), q0.coeffs());
  EXPECT_EQ(values.poseTranslation(X(3)), t0);
  EXPECT_EQ(report.num_constant_variables, 1u);
  EXPECT_EQ(report.num_free_parameters, 54);
  // The others moved towards the measurements.
  EXPECT_LT(report.final_cost, 0.1 * report.initial_cost);
}

TEST(GraphSolver, AProblemWithEverythingConstantIsSolvedTrivially) {
  PoseChain chain(41);
  Values values = chain.initial;
  std::set<Key> constant;
  for (int i = 0; i < 10; ++i) constant.insert(X(i));
  const SolveReport report = solve(chain.graph, values, SolverOptions(), constant);
  EXPECT_TRUE(report.usable) << report.toString();
  EXPECT_EQ(report.iterations, 0);
  EXPECT_EQ(report.num_free_parameters, 0);
  EXPECT_EQ(report.num_constant_variables, 10u);
  for (int i = 0; i < 10; ++i) {
    EXPECT_EQ(values.poseTranslation(X(i)), chain.initial.poseTranslation(X(i)));
  }
  // Nothing moved, so the cost per factor type is the same before and after.
  const FactorTypeReport& between = report.by_factor_type.at("TestBetweenFactor");
  EXPECT_EQ(between.count, 9u);
  EXPECT_GT(between.initial_cost, 0.0);
  EXPECT_EQ(between.initial_cost, between.final_cost);
}

TEST(GraphSolver, ReportSaysInPlainWordsWhatHappened) {
  LinearProblem linear(9);
  Values values = linear.initial;
  SolverOptions options;
  options.num_threads = 1;
  const SolveReport report = solve(linear.graph, values, options);
  const std::string text = report.toString();
  const std::string first_line = text.substr(0, text.find('\n'));
  EXPECT_TRUE(std::regex_match(
      first_line,
      std::regex("Levenberg–Marquardt with SPARSE_SCHUR \\(SuiteSparse\\): cost [0-9.e-]+ -> "
                 "[0-9.e-]+ in [0-9]+ iterations?, [0-9]+\\.[0-9] s; converged: (function|gradient|"
                 "parameter) tolerance reached")))
      << first_line;
  EXPECT_NE(text.find("\n  93 factors, 33 variables (0 constant, 30 landmarks eliminated), 99 "
                      "degrees of freedom, 1 thread"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n  LinearFactor: 93 factors, cost " + formatCost(report.initial_cost) +
                      " -> " + formatCost(report.final_cost)),
            std::string::npos)
      << text;
  EXPECT_EQ(report.termination, "converged");
  EXPECT_TRUE(report.converged);
  EXPECT_GT(report.iterations, 0);
  EXPECT_GE(report.wall_time_s, 0.0);
}

TEST(GraphSolver, ReportsAnIterationLimitAsNotConverged) {
  PoseChain chain(29);
  Values values = chain.initial;
  SolverOptions options;
  options.max_iterations = 1;
  options.num_threads = 1;
  const SolveReport report = solve(chain.graph, values, options);
  EXPECT_EQ(report.termination, "not converged");
  EXPECT_EQ(report.reason, "maximum number of iterations reached");
  EXPECT_FALSE(report.converged);
  EXPECT_TRUE(report.usable);
  EXPECT_EQ(report.iterations, 1);
  EXPECT_NE(report.toString().find("; not converged: maximum number of iterations reached"),
            std::string::npos);
}

TEST(GraphSolver, VerboseWritesOneLinePerIteration) {
  PoseChain chain(31);
  Values values = chain.initial;
  SolverOptions options;
  options.num_threads = 1;
  options.verbose = true;
  std::ostringstream progress;
  options.progress_stream = &progress;
  const SolveReport report = solve(chain.graph, values, options);
  const std::string text = progress.str();
  EXPECT_EQ(text.rfind("iteration 0: cost ", 0), 0u) << text;
  EXPECT_NE(text.find("\niteration 1: cost "), std::string::npos) << text;
  // One line for the initial state plus one per iteration.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), report.iterations + 1) << text;
}

TEST(GraphSolver, InvalidOptionsAreRejectedBeforeSolving) {
  PoseChain chain(37);
  Values values = chain.initial;
  SolverOptions options;
  options.max_iterations = -1;
  EXPECT_THROW(solve(chain.graph, values, options), std::invalid_argument);
  EXPECT_EQ(values.poseTranslation(X(1)), chain.initial.poseTranslation(X(1)));
}

TEST(GraphSolver, FormatCostPrintsThreeSignificantDigitsCompactly) {
  EXPECT_EQ(formatCost(1.2e6), "1.2e6");
  EXPECT_EQ(formatCost(3.4e2), "340");
  EXPECT_EQ(formatCost(1.23456e-5), "1.23e-5");
  EXPECT_EQ(formatCost(0.0), "0");
  EXPECT_EQ(formatCost(-2.5e10), "-2.5e10");
}

}  // namespace
}  // namespace hsmap
