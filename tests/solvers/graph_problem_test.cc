// GraphProblem: how a FactorGraph + Values become a ceres::Problem (blocks,
// manifolds, constants, bounds, robust losses, Schur ordering) and the errors
// for graphs that cannot be solved.

#include "solvers/graph_problem.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include <cmath>
#include <string>

#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using test::LinearFactor;

// r = x - b on one variable of dimension n (a prior), sigma 1.
std::shared_ptr<const LinearFactor> prior(Key key, const Eigen::VectorXd& b,
                                          RobustLoss loss = RobustLoss::none()) {
  return std::make_shared<LinearFactor>(
      std::vector<Key>{key}, std::vector<Eigen::MatrixXd>{Eigen::MatrixXd::Identity(b.size(), b.size())},
      b, NoiseModel::isotropic(static_cast<int>(b.size()), 1.0), loss);
}

// r = x_b - x_a on two variables of dimension n.
std::shared_ptr<const LinearFactor> difference(Key a, Key b, int n) {
  return std::make_shared<LinearFactor>(
      std::vector<Key>{a, b},
      std::vector<Eigen::MatrixXd>{-Eigen::MatrixXd::Identity(n, n), Eigen::MatrixXd::Identity(n, n)},
      Eigen::VectorXd::Zero(n), NoiseModel::isotropic(n, 1.0));
}

std::string constructionError(const FactorGraph& graph, Values& values,
                              GraphProblemOptions options = {}) {
  try {
    GraphProblem problem(graph, values, std::move(options));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(GraphProblem, ListsTheFirstMissingVariablesWithTheFactorsThatUseThem) {
  FactorGraph graph;
  Values values;
  values.insertPoint(L(0), Eigen::Vector3d::Zero());
  for (int i = 0; i < 7; ++i) graph.add(difference(L(i), L(i + 1), 3));
  EXPECT_EQ(constructionError(graph, values),
            "GraphProblem: 7 variables used by factors have no value in Values: "
            "l1 (used by factor #0 (LinearFactor)), l2 (used by factor #1 (LinearFactor)), "
            "l3 (used by factor #2 (LinearFactor)), l4 (used by factor #3 (LinearFactor)), "
            "l5 (used by factor #4 (LinearFactor)) and 2 more");
}

TEST(GraphProblem, RejectsAFactorThatIsNotACeresFactor) {
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 1.0);
  graph.add(prior(D(0), Eigen::VectorXd::Ones(1)));
  graph.emplace<test::NotACeresFactor>(D(0));
  EXPECT_EQ(constructionError(graph, values),
            "GraphProblem: factor #1 (NotACeresFactor) is not a CeresFactor, so the Ceres solver "
            "cannot evaluate it");
}

TEST(GraphProblem, RejectsABlockSizeThatDoesNotMatchTheValue) {
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 1.0);
  graph.add(prior(D(0), Eigen::Vector3d::Zero()));
  EXPECT_EQ(constructionError(graph, values),
            "GraphProblem: factor #0 (LinearFactor) expects a block of 3 doubles for d0, but "
            "Values holds a scalar of 1 double");
}

TEST(GraphProblem, RejectsAResidualCountThatDoesNotMatchTheNoiseModel) {
  FactorGraph graph;
  Values values;
  values.insertPoint(L(0), Eigen::Vector3d::Zero());
  graph.emplace<LinearFactor>(std::vector<Key>{L(0)},
                              std::vector<Eigen::MatrixXd>{Eigen::Matrix3d::Identity()},
                              Eigen::VectorXd(Eigen::Vector3d::Zero()), NoiseModel::isotropic(2, 1.0));
  EXPECT_EQ(constructionError(graph, values),
            "GraphProblem: factor #0 (LinearFactor) returns 3 residuals but its noise model has "
            "dimension 2");
}

TEST(GraphProblem, RejectsAConstantKeyThatNamesNoVariable) {
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 1.0);
  values.insertScalar(D(1), 1.0);
  graph.add(prior(D(0), Eigen::VectorXd::Ones(1)));
  GraphProblemOptions options;
  // d1 has a value but no factor: accepted, nothing to hold.
  options.constant = {D(1)};
  {
    GraphProblem problem(graph, values, options);
    EXPECT_EQ(problem.numConstantVariables(), 0u);
    EXPECT_EQ(problem.numFreeParameters(), 1);
  }
  options.constant = {D(1), X(4)};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: constant variable x4 is neither used by a factor of the graph nor "
            "present in Values");
}

TEST(GraphProblem, HasOneBlockPerVariableInKeyOrderWithTheSe3ManifoldOnPosesOnly) {
  FactorGraph graph;
  Values values;
  values.insertPose(X(0), Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 2.0, 3.0));
  values.insertPoint(L(0), Eigen::Vector3d(4.0, 5.0, 6.0));
  values.insertPoint(L(9), Eigen::Vector3d::Zero());  // unused: not in the problem
  graph.emplace<test::TestPosePriorFactor>(X(0), SE3d(), NoiseModel::isotropic(6, 1.0));
  graph.add(prior(L(0), Eigen::Vector3d::Ones()));
  GraphProblemOptions options;
  options.constant = {L(0)};
  GraphProblem problem(graph, values, options);
  ceres::Problem& ceres_problem = problem.problem();
  EXPECT_EQ(ceres_problem.NumParameterBlocks(), 2);
  EXPECT_EQ(ceres_problem.NumResidualBlocks(), 2);
  EXPECT_TRUE(ceres_problem.HasParameterBlock(problem.block(X(0))));
  EXPECT_TRUE(ceres_problem.HasParameterBlock(problem.block(L(0))));
  EXPECT_THROW(problem.block(L(9)), std::out_of_range);
  ASSERT_NE(ceres_problem.GetManifold(problem.block(X(0))), nullptr);
  EXPECT_EQ(ceres_problem.ParameterBlockTangentSize(problem.block(X(0))), 6);
  EXPECT_EQ(ceres_problem.GetManifold(problem.block(L(0))), nullptr);
  EXPECT_TRUE(ceres_problem.IsParameterBlockConstant(problem.block(L(0))));
  EXPECT_EQ(problem.numConstantVariables(), 1u);
  EXPECT_FALSE(ceres_problem.IsParameterBlockConstant(problem.block(X(0))));
  EXPECT_EQ(problem.variables(), (std::vector<Key>{X(0), L(0)}));
  EXPECT_EQ(problem.numFreeParameters(), 6);
  // One buffer in key order (Ceres orders a group's blocks by address), the
  // values copied in, and back out when asked.
  EXPECT_EQ(problem.block(L(0)), problem.block(X(0)) + values.size(X(0)));
  for (int i = 0; i < values.size(X(0)); ++i) EXPECT_EQ(problem.block(X(0))[i], values.data(X(0))[i]);
  EXPECT_EQ(problem.block(L(0))[2], 6.0);
  problem.block(L(0))[2] = 7.0;
  EXPECT_EQ(values.data(L(0))[2], 6.0);
  problem.storeValues();
  EXPECT_EQ(values.data(L(0))[2], 7.0);
  values.data(L(0))[2] = 8.0;
  problem.loadValues();
  EXPECT_EQ(problem.block(L(0))[2], 8.0);
}

TEST(GraphProblem, RobustLossesApplyToTheWhitenedResidualInSigmas) {
  // d = 3 with a unit-sigma prior at 0: whitened |r| = 3 sigmas.
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 3.0);
  graph.add(prior(D(0), Eigen::VectorXd::Zero(1)));
  values.insertScalar(D(1), 3.0);
  graph.add(prior(D(1), Eigen::VectorXd::Zero(1), RobustLoss::huber(1.0)));
  values.insertScalar(D(2), 3.0);
  graph.add(prior(D(2), Eigen::VectorXd::Zero(1), RobustLoss::cauchy(2.0)));
  values.insertScalar(D(3), 0.5);
  graph.add(prior(D(3), Eigen::VectorXd::Zero(1), RobustLoss::huber(1.0)));
  GraphProblem problem(graph, values);

  const std::map<std::string, FactorTypeCost> costs = problem.costByFactorType();
  ASSERT_EQ(costs.size(), 1u);
  const FactorTypeCost& linear = costs.at("LinearFactor");
  EXPECT_EQ(linear.count, 4u);
  // 0.5 * 9  +  0.5 * (2 * 1 * 3 - 1)  +  0.5 * 4 log(1 + 9/4)  +  0.5 * 0.25
  const double expected = 4.5 + 2.5 + 2.0 * std::log(1.0 + 9.0 / 4.0) + 0.125;
  EXPECT_NEAR(linear.cost, expected, 1e-12);
  EXPECT_EQ(linear.beyond_loss_scale, 2u);  // d1 and d2; d3 is inside its scale

  double ceres_cost = 0.0;
  ASSERT_TRUE(problem.problem().Evaluate(ceres::Problem::EvaluateOptions(), &ceres_cost, nullptr,
                                         nullptr, nullptr));
  EXPECT_NEAR(ceres_cost, expected, 1e-12);
}

TEST(GraphProblem, SchurOrderingEliminatesAnIndependentSetOfFreeLandmarks) {
  FactorGraph graph;
  Values values;
  values.insertVector(K(0), Eigen::Vector3d::Zero());
  values.insertVector(K(1), Eigen::Vector3d::Zero());
  for (int i = 0; i < 5; ++i) values.insertPoint(L(i), Eigen::Vector3d::Zero());
  graph.add(difference(K(0), L(0), 3));
  graph.add(difference(K(0), L(1), 3));
  graph.add(difference(K(1), L(2), 3));
  graph.add(difference(L(2), L(3), 3));  // l3 touches l2: not both can be eliminated
  graph.add(difference(K(1), L(4), 3));
  GraphProblemOptions options;
  options.constant = {L(4)};
  GraphProblem problem(graph, values, options);
  EXPECT_EQ(problem.numEliminatedLandmarks(), 3u);
  const auto ordering = problem.schurOrdering();
  ASSERT_NE(ordering, nullptr);
  EXPECT_EQ(ordering->NumGroups(), 2);
  EXPECT_EQ(ordering->NumElements(), 7);
  EXPECT_EQ(ordering->GroupId(problem.block(L(0))), 0);
  EXPECT_EQ(ordering->GroupId(problem.block(L(1))), 0);
  EXPECT_EQ(ordering->GroupId(problem.block(L(2))), 0);
  EXPECT_EQ(ordering->GroupId(problem.block(L(3))), 1);
  EXPECT_EQ(ordering->GroupId(problem.block(L(4))), 1);
  EXPECT_EQ(ordering->GroupId(problem.block(K(0))), 1);
  EXPECT_EQ(ordering->GroupId(problem.block(K(1))), 1);
}

TEST(GraphProblem, NoSchurOrderingWithoutLandmarks) {
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 0.0);
  graph.add(prior(D(0), Eigen::VectorXd::Ones(1)));
  GraphProblem problem(graph, values);
  EXPECT_EQ(problem.schurOrdering(), nullptr);
}

TEST(GraphProblem, SetsBoundsAndRejectsUnsoundOnes) {
  FactorGraph graph;
  Values values;
  values.insertScalar(D(0), 0.01);
  values.insertPose(X(0), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  graph.add(prior(D(0), Eigen::VectorXd::Ones(1)));
  graph.emplace<test::TestPosePriorFactor>(X(0), SE3d(), NoiseModel::isotropic(6, 1.0));

  GraphProblemOptions options;
  options.bounds = {{D(0), 0, -0.5, 0.5}};
  {
    GraphProblem problem(graph, values, options);
    EXPECT_EQ(problem.problem().GetParameterLowerBound(problem.block(D(0)), 0), -0.5);
    EXPECT_EQ(problem.problem().GetParameterUpperBound(problem.block(D(0)), 0), 0.5);
  }
  options.bounds = {{X(0), 4, -1.0, 1.0}};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: bound on x0: bounds on poses are not supported (quaternion components "
            "have no meaning on their own)");
  options.bounds = {{D(0), 1, -1.0, 1.0}};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: bound on d0: index 1 is outside [0, 1)");
  options.bounds = {{D(0), 0, 1.0, -1.0}};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: bound on d0[0]: lower 1 must be below upper -1");
  options.bounds = {{D(0), 0, 0.1, 0.2}};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: bound on d0[0]: the current value 0.01 lies outside [0.1, 0.2]");
  options.bounds = {{D(5), 0, 0.1, 0.2}};
  EXPECT_EQ(constructionError(graph, values, options),
            "GraphProblem: bound on d5: the variable is not used by any factor of the graph");
}

}  // namespace
}  // namespace hsmap
