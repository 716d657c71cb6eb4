// GraphProblemOptions::constant_components: single doubles of a vector held
// at their value (SubsetManifold) while the others are solved, and the
// covariance over the free components only.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <stdexcept>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/pushbroom_intrinsics_prior_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"

namespace hsmap {
namespace {

TEST(ConstantComponents, HoldTheirValueAndLeaveTheCovarianceOverTheFreeOnes) {
  FactorGraph graph;
  graph.emplace<PushbroomIntrinsicsPriorFactor>(K(0), PushbroomIntrinsicsPriorFactor::Intrinsics{1500, 960, 0.02, 0},
                                                PushbroomIntrinsicsPriorFactor::Intrinsics{15, 3, 0, 0.01});
  Values values;
  values.insertVector(K(0), Eigen::Vector4d(1490, 965, 0.05, 0.004));
  GraphProblemOptions options;
  options.constant_components[K(0)] = {2};
  GraphProblem problem(graph, values, options);
  EXPECT_EQ(problem.tangentSize(K(0)), 3);
  EXPECT_EQ(problem.numFreeParameters(), 3);
  ASSERT_TRUE(solve(problem, SolverOptions{}).usable);
  const Eigen::VectorXd k = values.vector(K(0));
  EXPECT_NEAR(k[0], 1500.0, 1e-6);
  EXPECT_NEAR(k[1], 960.0, 1e-6);
  EXPECT_EQ(k[2], 0.05);  // held
  EXPECT_NEAR(k[3], 0.0, 1e-9);
  for (const auto algorithm : {CovarianceOptions::Algorithm::sparse_qr, CovarianceOptions::Algorithm::landmark_schur}) {
    CovarianceOptions covariance_options;
    covariance_options.algorithm = algorithm;
    const Eigen::MatrixXd covariance = jointMarginalCovariance(problem, {K(0)}, covariance_options);
    ASSERT_EQ(covariance.rows(), 3);
    EXPECT_TRUE(covariance.isApprox(Eigen::Vector3d(225.0, 9.0, 1e-4).asDiagonal().toDenseMatrix(), 1e-9))
        << covariance;
  }
}

TEST(ConstantComponents, RejectAnIndexOutsideTheVariable) {
  FactorGraph graph;
  graph.emplace<PushbroomIntrinsicsPriorFactor>(K(0), PushbroomIntrinsicsPriorFactor::Intrinsics{1500, 960, 0, 0},
                                                PushbroomIntrinsicsPriorFactor::Intrinsics{15, 3, 0.01, 0.01});
  Values values;
  values.insertVector(K(0), Eigen::Vector4d(1500, 960, 0, 0));
  GraphProblemOptions options;
  options.constant_components[K(0)] = {4};
  EXPECT_THROW(GraphProblem(graph, values, options), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
