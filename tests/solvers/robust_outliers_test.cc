// factorsBeyondLossScale(): the robust factors beyond their loss scale, in
// closed form on linear factors and after a bundle adjustment with a few
// corrupted observations (exactly those are returned), in agreement with
// the solve report's counts.

#include "solvers/robust_outliers.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "factors/ins_attitude_factor.h"
#include "factors/ins_position_factor.h"
#include "factors/reprojection_factor.h"
#include "solvers/graph_solver.h"
#include "tests/support/synthetic_transect.h"
#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using test::LinearFactor;

// r = x - b on a scalar K(0) = 0 with sigma 1: the whitened norm is |b|.
void addScalarFactor(FactorGraph& graph, double b, RobustLoss loss) {
  graph.emplace<LinearFactor>(std::vector<Key>{K(0)},
                              std::vector<Eigen::MatrixXd>{Eigen::MatrixXd::Identity(1, 1)},
                              Eigen::VectorXd::Constant(1, b), NoiseModel::isotropic(1, 1.0),
                              loss);
}

TEST(FactorsBeyondLossScale, ListsRobustFactorsBeyondTheirScaleInSigmas) {
  FactorGraph graph;
  Values values;
  values.insertVector(K(0), Eigen::VectorXd::Zero(1));
  addScalarFactor(graph, 5.0, RobustLoss::cauchy(3.0));    // 0: 5 sigmas > 3: listed
  addScalarFactor(graph, 100.0, RobustLoss::none());       // 1: no robust loss: never listed
  addScalarFactor(graph, 2.0, RobustLoss::huber(3.0));     // 2: inside the scale
  addScalarFactor(graph, -3.5, RobustLoss::huber(3.0));    // 3: listed (the norm counts)
  addScalarFactor(graph, 3.0, RobustLoss::huber(3.0));     // 4: exactly at the scale: not beyond
  graph.emplace<LinearFactor>(std::vector<Key>{K(0)},     // 5: 2 px with sigma 0.5 = 4 sigmas
                              std::vector<Eigen::MatrixXd>{Eigen::MatrixXd::Identity(1, 1)},
                              Eigen::VectorXd::Constant(1, 2.0), NoiseModel::isotropic(1, 0.5),
                              RobustLoss::cauchy(3.0));
  EXPECT_EQ(factorsBeyondLossScale(graph, values), (std::vector<std::size_t>{0, 3, 5}));

  Values copy = values;
  const GraphProblem problem(graph, copy);
  EXPECT_EQ(factorsBeyondLossScale(problem), (std::vector<std::size_t>{0, 3, 5}));
  const std::vector<FactorEvaluation> evaluations = problem.evaluateFactors();
  ASSERT_EQ(evaluations.size(), 6u);
  EXPECT_DOUBLE_EQ(evaluations[1].whitened_norm, 100.0);
  EXPECT_DOUBLE_EQ(evaluations[1].cost, 0.5 * 100.0 * 100.0);
  EXPECT_FALSE(evaluations[1].beyond_loss_scale);
  EXPECT_DOUBLE_EQ(evaluations[5].whitened_norm, 4.0);
}

TEST(FactorsBeyondLossScale, AGraphThatCannotBeEvaluatedThrows) {
  FactorGraph graph;
  addScalarFactor(graph, 1.0, RobustLoss::huber(1.0));
  EXPECT_THROW(factorsBeyondLossScale(graph, Values()), std::invalid_argument);
}

// A keyframe bundle adjustment (8 keyframes, 150 landmarks, INS on every
// keyframe) whose pixels carry 0.2 px of noise under a 1 px noise model, so
// no clean observation comes near the Cauchy scale of 3 sigmas, and a few
// observations corrupted by ~30 px.
struct CorruptedBundleAdjustment {
  test::Transect transect;
  FactorGraph graph;
  Values values;
  std::vector<std::size_t> corrupted;  // factor indices = observation indices
};

CorruptedBundleAdjustment makeCorruptedBundleAdjustment() {
  test::TransectConfig config;
  config.seed = 7;
  config.num_keyframes = 8;
  config.num_landmarks = 150;
  config.pixel_sigma = 0.2;
  config.start_pose_sigma_m = 0.05;
  config.start_pose_sigma_deg = 0.5;
  config.start_landmark_sigma_m = 0.05;
  CorruptedBundleAdjustment ba{test::makeTransect(config), {}, {}, {}};
  const std::size_t n = ba.transect.observations.size();
  ba.corrupted = {5, n / 5, n / 3, n / 2, 3 * n / 4, n - 2};
  std::vector<test::PixelObservation> observations = ba.transect.observations;
  for (const std::size_t i : ba.corrupted) observations[i].pixel += Eigen::Vector2d(25.0, -18.0);

  const NoiseModel pixel_noise = NoiseModel::isotropic(2, 1.0);
  for (const test::PixelObservation& observation : observations) {
    ba.graph.emplace<ReprojectionFactor>(X(observation.keyframe), L(observation.landmark),
                                         observation.pixel, ba.transect.camera, pixel_noise,
                                         RobustLoss::cauchy(3.0));
  }
  for (std::size_t k = 0; k < ba.transect.T_W_C.size(); ++k) {
    ba.graph.emplace<InsPositionFactor>(X(k), ba.transect.ins_p_W_B[k], ba.transect.T_B_C,
                                        test::insPositionNoise(config));
    ba.graph.emplace<InsAttitudeFactor>(X(k), ba.transect.ins_q_W_B[k], ba.transect.T_B_C,
                                        test::insAttitudeNoise(config));
    ba.values.insertPose(X(k), ba.transect.start_T_W_C[k].q, ba.transect.start_T_W_C[k].t);
  }
  for (std::size_t i = 0; i < ba.transect.p_W.size(); ++i) {
    ba.values.insertPoint(L(i), ba.transect.start_p_W[i]);
  }
  return ba;
}

TEST(FactorsBeyondLossScale, ReturnsExactlyTheCorruptedObservationsAfterABundleAdjustment) {
  CorruptedBundleAdjustment ba = makeCorruptedBundleAdjustment();
  ASSERT_GT(ba.transect.observations.size(), 600u);

  // At the start (5 cm / 0.5 deg off) many clean observations are beyond too.
  const Values start = ba.values;
  const std::vector<std::size_t> at_start = factorsBeyondLossScale(ba.graph, ba.values);
  EXPECT_GT(at_start.size(), 2 * ba.corrupted.size());
  // The values were only read.
  EXPECT_EQ(ba.values.poseTranslation(X(3)), start.poseTranslation(X(3)));
  EXPECT_EQ(ba.values.point(L(10)), start.point(L(10)));

  SolverOptions options;
  options.num_threads = 2;
  GraphProblem problem(ba.graph, ba.values);
  const SolveReport report = solve(problem, options);
  ASSERT_TRUE(report.converged) << report.toString();

  const std::vector<std::size_t> beyond = factorsBeyondLossScale(ba.graph, ba.values);
  EXPECT_EQ(beyond, ba.corrupted) << report.toString();
  EXPECT_EQ(factorsBeyondLossScale(problem, 2), beyond);
  // The same test as the report's counts.
  std::size_t reported = 0;
  for (const auto& [name, entry] : report.by_factor_type) reported += entry.final_beyond_loss_scale;
  EXPECT_EQ(reported, beyond.size());
}

}  // namespace
}  // namespace hsmap
