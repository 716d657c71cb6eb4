// landmark_schur covariances (solvers/landmark_schur_covariance.h) against
// ceres::Covariance (sparse_qr, dense_svd) on a small bundle adjustment:
// keyframe poses with INS factors, landmarks seen by reprojections, an
// extrinsic pose e0 with a prior and a between factor, a scalar d0 with a
// prior and a factor coupling it to a pose (in ambient coordinates, so the
// manifold's PlusJacobian matters) and a landmark, and a factor between two
// landmarks (so one of them cannot be eliminated and stays in the reduced
// system). Marginal and joint calls, with and without a robust loss, constants,
// the free-gauge error and the size limit.

#include "solvers/landmark_schur_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>
#include <vector>

#include "solvers/marginal_covariance.h"
#include "tests/solvers/test_factors.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

using Algorithm = CovarianceOptions::Algorithm;

constexpr double kRelativeTolerance = 1e-9;

CovarianceOptions optionsFor(Algorithm algorithm, bool apply_loss_function = true) {
  CovarianceOptions options;
  options.algorithm = algorithm;
  options.num_threads = 2;
  options.apply_loss_function = apply_loss_function;
  return options;
}

Eigen::MatrixXd randomMatrix(std::mt19937& rng, int rows, int cols, double scale) {
  std::normal_distribution<double> normal(0.0, scale);
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) m(i, j) = normal(rng);
  return m;
}

struct Scene {
  test::Transect transect;
  FactorGraph graph;
  Values values;
};

// The bundle adjustment at its (perturbed) start values; the covariances are
// compared at whatever point J is evaluated. `absolute` adds the INS factors
// and the priors that fix the gauge.
Scene makeScene(RobustLoss loss, bool absolute = true) {
  test::TransectConfig config;
  config.seed = 7;
  config.num_keyframes = 8;
  config.num_landmarks = 60;
  Scene scene;
  scene.transect = test::makeTransect(config);
  const test::Transect& transect = scene.transect;
  FactorGraph& graph = scene.graph;
  Values& values = scene.values;
  if (absolute) {
    test::buildBundleAdjustment(transect, loss, &graph, &values);
  } else {
    const NoiseModel pixel_noise = NoiseModel::isotropic(2, transect.config.pixel_sigma);
    for (const test::PixelObservation& observation : transect.observations) {
      graph.emplace<ReprojectionFactor>(X(observation.keyframe), L(observation.landmark),
                                        observation.pixel, transect.camera, pixel_noise, loss);
    }
    for (std::size_t k = 0; k < transect.T_W_C.size(); ++k) {
      values.insertPose(X(k), transect.start_T_W_C[k].q, transect.start_T_W_C[k].t);
    }
    for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
      values.insertPoint(L(i), transect.start_p_W[i]);
    }
    return scene;
  }

  std::mt19937 rng(11);
  // e0 = T_C_U-like extrinsic: a prior and a between factor to x0.
  const SE3d extrinsic = transect.T_B_C;
  values.insertPose(E(0), extrinsic.q, extrinsic.t);
  graph.emplace<test::TestPosePriorFactor>(
      E(0), extrinsic * SE3d::exp(Vector6d::Constant(0.01)),
      NoiseModel::fromSigmas((Vector6d() << 0.05, 0.05, 0.05, 0.02, 0.02, 0.02).finished()));
  graph.emplace<test::TestBetweenFactor>(
      X(0), E(0), transect.start_T_W_C[0].inverse() * extrinsic * SE3d::exp(Vector6d::Constant(-0.02)),
      NoiseModel::isotropic(6, 0.1));
  // d0: a prior, and a linear factor on (d0, x1 in ambient [q t], l3).
  values.insertScalar(D(0), 0.03);
  graph.emplace<test::LinearFactor>(std::vector<Key>{D(0)},
                                    std::vector<Eigen::MatrixXd>{Eigen::MatrixXd::Identity(1, 1)},
                                    Eigen::VectorXd::Constant(1, 0.01), NoiseModel::isotropic(1, 0.2));
  graph.emplace<test::LinearFactor>(
      std::vector<Key>{D(0), X(1), L(3)},
      std::vector<Eigen::MatrixXd>{randomMatrix(rng, 2, 1, 1.0), randomMatrix(rng, 2, 7, 1.0),
                                   randomMatrix(rng, 2, 3, 1.0)},
      Eigen::VectorXd::Zero(2), NoiseModel::isotropic(2, 0.05), loss);
  // l5 - l6: l6 shares a factor with l5, so it is not eliminated.
  graph.emplace<test::LinearFactor>(
      std::vector<Key>{L(5), L(6)},
      std::vector<Eigen::MatrixXd>{-Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Identity(3, 3)},
      Eigen::VectorXd(transect.start_p_W[6] - transect.start_p_W[5]), NoiseModel::isotropic(3, 0.02));
  return scene;
}

double relativeError(const Eigen::MatrixXd& actual, const Eigen::MatrixXd& expected) {
  return (actual - expected).norm() / expected.norm();
}

void expectMarginalsMatch(GraphProblem& problem, const std::vector<Key>& keys,
                          Algorithm reference, bool apply_loss_function = true) {
  const auto expected = marginalCovariances(problem, keys, optionsFor(reference, apply_loss_function));
  const auto actual =
      marginalCovariances(problem, keys, optionsFor(Algorithm::landmark_schur, apply_loss_function));
  ASSERT_EQ(actual.size(), keys.size());
  for (const Key& key : keys) {
    const Eigen::MatrixXd& a = actual.at(key);
    const Eigen::MatrixXd& e = expected.at(key);
    ASSERT_EQ(a.rows(), e.rows()) << key.toString();
    ASSERT_EQ(a.cols(), e.cols()) << key.toString();
    if (e.norm() == 0.0) {
      EXPECT_EQ(a, e) << key.toString();
      continue;
    }
    EXPECT_LT(relativeError(a, e), kRelativeTolerance) << key.toString() << "\n" << a << "\n\n" << e;
  }
}

void expectJointMatches(GraphProblem& problem, const std::vector<Key>& keys, Algorithm reference,
                        bool apply_loss_function = true) {
  const Eigen::MatrixXd expected =
      jointMarginalCovariance(problem, keys, optionsFor(reference, apply_loss_function));
  const Eigen::MatrixXd actual =
      jointMarginalCovariance(problem, keys, optionsFor(Algorithm::landmark_schur, apply_loss_function));
  ASSERT_EQ(actual.rows(), expected.rows());
  ASSERT_EQ(actual.cols(), expected.cols());
  EXPECT_LT(relativeError(actual, expected), kRelativeTolerance) << actual << "\n\n" << expected;
}

TEST(LandmarkSchurCovariance, TheSceneEliminatesLandmarksAndKeepsOneInTheReducedSystem) {
  Scene scene = makeScene(RobustLoss::none());
  GraphProblem problem(scene.graph, scene.values);
  const std::vector<Key>& eliminated = problem.eliminatedLandmarks();
  EXPECT_EQ(eliminated.size(), scene.transect.p_W.size() - 1);
  EXPECT_EQ(eliminated.size(), problem.numEliminatedLandmarks());
  EXPECT_TRUE(std::find(eliminated.begin(), eliminated.end(), L(5)) != eliminated.end());
  EXPECT_TRUE(std::find(eliminated.begin(), eliminated.end(), L(6)) == eliminated.end());
}

TEST(LandmarkSchurCovariance, MarginalsEqualSparseQrAndDenseSvd) {
  Scene scene = makeScene(RobustLoss::none());
  GraphProblem problem(scene.graph, scene.values);
  // Poses, the extrinsic, the scalar, eliminated landmarks (l3 is coupled to
  // d0 and x1) and the landmark kept in the reduced system (l6).
  const std::vector<Key> keys{X(0), X(3), E(0), D(0), L(0), L(3), L(5), L(6)};
  {
    SCOPED_TRACE("sparse_qr");
    expectMarginalsMatch(problem, keys, Algorithm::sparse_qr);
  }
  {
    SCOPED_TRACE("dense_svd");
    expectMarginalsMatch(problem, keys, Algorithm::dense_svd);
  }
}

TEST(LandmarkSchurCovariance, MarginalsOfEveryVariableEqualSparseQr) {
  // As many columns as the reduced system: the path that inverts S once.
  Scene scene = makeScene(RobustLoss::none());
  GraphProblem problem(scene.graph, scene.values);
  expectMarginalsMatch(problem, problem.variables(), Algorithm::sparse_qr);
}

TEST(LandmarkSchurCovariance, JointCovariancesEqualSparseQr) {
  Scene scene = makeScene(RobustLoss::none());
  GraphProblem problem(scene.graph, scene.values);
  {
    SCOPED_TRACE("{e0, d0}");
    expectJointMatches(problem, {E(0), D(0)}, Algorithm::sparse_qr);
  }
  {
    SCOPED_TRACE("poses, scalar and landmarks, mixed order");
    expectJointMatches(problem, {L(3), X(2), D(0), L(6), E(0), L(7), X(1)}, Algorithm::sparse_qr);
  }
  {
    SCOPED_TRACE("dense_svd");
    expectJointMatches(problem, {X(1), D(0), L(3)}, Algorithm::dense_svd);
  }
}

TEST(LandmarkSchurCovariance, RobustLossIsAppliedAsByCeres) {
  // At the perturbed start many pixels are beyond the Cauchy scale, so the
  // robustified Jacobian differs markedly from the plain one.
  Scene scene = makeScene(RobustLoss::cauchy(1.0));
  GraphProblem problem(scene.graph, scene.values);
  const std::vector<Key> keys{X(2), E(0), D(0), L(3), L(6), L(9)};
  expectMarginalsMatch(problem, keys, Algorithm::sparse_qr);
  expectJointMatches(problem, keys, Algorithm::sparse_qr);
  {
    SCOPED_TRACE("apply_loss_function = false");
    expectMarginalsMatch(problem, keys, Algorithm::sparse_qr, false);
    expectJointMatches(problem, keys, Algorithm::sparse_qr, false);
  }
  const Eigen::MatrixXd robust =
      jointMarginalCovariance(problem, {E(0), D(0)}, optionsFor(Algorithm::landmark_schur));
  const Eigen::MatrixXd plain =
      jointMarginalCovariance(problem, {E(0), D(0)}, optionsFor(Algorithm::landmark_schur, false));
  EXPECT_GT(relativeError(robust, plain), 1e-3);
}

TEST(LandmarkSchurCovariance, PassesOfAFewResidualBlocksGiveTheOnePassResult) {
  // The Jacobian reduced a few residual blocks at a time (a landmark's
  // observations, and the reduced variables' factors, split across passes)
  // against one pass over all of them and against sparse_qr.
  Scene scene = makeScene(RobustLoss::cauchy(1.0));
  ASSERT_GT(scene.graph.size(), 50u);
  GraphProblem problem(scene.graph, scene.values);
  const std::vector<Key> keys{X(2), E(0), D(0), L(3), L(6), L(9)};
  CovarianceOptions one_pass = optionsFor(Algorithm::landmark_schur);
  one_pass.residual_blocks_per_pass = 1000000;
  const Eigen::MatrixXd expected = jointMarginalCovariance(problem, keys, one_pass);
  const Eigen::MatrixXd reference =
      jointMarginalCovariance(problem, keys, optionsFor(Algorithm::sparse_qr));
  EXPECT_LT(relativeError(expected, reference), kRelativeTolerance);
  for (const std::size_t per_pass : {std::size_t(1), std::size_t(7), std::size_t(50)}) {
    CovarianceOptions options = optionsFor(Algorithm::landmark_schur);
    options.residual_blocks_per_pass = per_pass;
    const Eigen::MatrixXd actual = jointMarginalCovariance(problem, keys, options);
    EXPECT_LT(relativeError(actual, expected), 1e-12) << per_pass << " per pass";
  }
}

TEST(LandmarkSchurCovariance, ConstantVariablesHaveZeroCovariance) {
  Scene scene = makeScene(RobustLoss::none());
  GraphProblemOptions options;
  options.constant = {X(0), L(4)};
  GraphProblem problem(scene.graph, scene.values, options);
  const std::vector<Key> keys{X(0), L(4), X(1), E(0), D(0), L(3)};
  expectMarginalsMatch(problem, keys, Algorithm::sparse_qr);
  expectJointMatches(problem, keys, Algorithm::sparse_qr);
  const auto marginals = marginalCovariances(problem, keys, optionsFor(Algorithm::landmark_schur));
  EXPECT_EQ(marginals.at(X(0)), Eigen::MatrixXd::Zero(6, 6));
  EXPECT_EQ(marginals.at(L(4)), Eigen::MatrixXd::Zero(3, 3));
}

TEST(LandmarkSchurCovariance, WithoutLandmarksItIsADenseCholeskyOfTheWholeSystem) {
  // Poses with priors and between factors only: nothing to eliminate.
  std::mt19937 rng(13);
  FactorGraph graph;
  Values values;
  SE3d pose = test::randomPose(rng, 5.0);
  for (int k = 0; k < 5; ++k) {
    values.insertPose(X(k), pose.q, pose.t);
    graph.emplace<test::TestPosePriorFactor>(X(k), pose * SE3d::exp(Vector6d::Constant(0.01 * k)),
                                             NoiseModel::isotropic(6, 0.5 + 0.1 * k));
    if (k > 0) {
      graph.emplace<test::TestBetweenFactor>(X(k - 1), X(k), test::randomPose(rng, 1.0),
                                             NoiseModel::isotropic(6, 0.05));
    }
    pose = pose * test::randomPose(rng, 1.0);
  }
  GraphProblem problem(graph, values);
  ASSERT_EQ(problem.numEliminatedLandmarks(), 0u);
  expectMarginalsMatch(problem, {X(0), X(2), X(4)}, Algorithm::sparse_qr);
  expectJointMatches(problem, {X(3), X(1)}, Algorithm::sparse_qr);
}

TEST(LandmarkSchurCovariance, OnlyConstantKeysGiveZeros) {
  Scene scene = makeScene(RobustLoss::none());
  GraphProblemOptions options;
  options.constant = {X(0), D(0)};
  GraphProblem problem(scene.graph, scene.values, options);
  const Eigen::MatrixXd joint =
      jointMarginalCovariance(problem, {D(0), X(0)}, optionsFor(Algorithm::landmark_schur));
  EXPECT_EQ(joint, Eigen::MatrixXd::Zero(7, 7));
}

void expectRankDeficient(GraphProblem& problem, const std::vector<Key>& keys) {
  try {
    marginalCovariances(problem, keys, optionsFor(Algorithm::landmark_schur));
    FAIL() << "expected CovarianceRankDeficient";
  } catch (const CovarianceRankDeficient& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("marginal covariance: the problem is rank deficient"), std::string::npos) << what;
    EXPECT_NE(what.find("over the " + std::to_string(problem.numFreeParameters()) +
                        " free degrees of freedom"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("hold one pose constant (e.g. constant = {X(0)})"), std::string::npos) << what;
  }
  EXPECT_THROW(jointMarginalCovariance(problem, keys, optionsFor(Algorithm::landmark_schur)),
               CovarianceRankDeficient);
}

TEST(LandmarkSchurCovariance, AFreeGaugeIsReportedAsRankDeficient) {
  // Reprojections only: a similarity transform of the scene leaves every
  // residual unchanged (7-dimensional null space).
  Scene scene = makeScene(RobustLoss::none(), /*absolute=*/false);
  {
    GraphProblem problem(scene.graph, scene.values);
    ASSERT_GT(problem.numEliminatedLandmarks(), 0u);
    expectRankDeficient(problem, {X(0), X(1)});
  }
  // Fixing one pose leaves the scale free: still rank deficient.
  {
    GraphProblemOptions options;
    options.constant = {X(0)};
    GraphProblem problem(scene.graph, scene.values, options);
    expectRankDeficient(problem, {X(1)});
  }
}

TEST(LandmarkSchurCovariance, ALandmarkSeenOnceIsRankDeficient) {
  // One reprojection fixes only 2 of the landmark's 3 coordinates: its 3x3
  // block of J^T J is singular.
  Scene scene = makeScene(RobustLoss::none());
  const test::Transect& transect = scene.transect;
  scene.values.insertPoint(L(1000), transect.p_W[0]);
  const test::PixelObservation& observation = transect.observations.front();
  scene.graph.emplace<ReprojectionFactor>(X(observation.keyframe), L(1000), observation.pixel,
                                          transect.camera, NoiseModel::isotropic(2, 0.5));
  GraphProblem problem(scene.graph, scene.values);
  expectRankDeficient(problem, {E(0)});
}

TEST(LandmarkSchurCovariance, TwoPointsWithOnlyRelativeFactorsAreRankDeficient) {
  // As in marginal_covariance_test: l0 is eliminated, l1 is not (they share
  // the factors), and the Schur complement of l1 is exactly zero.
  FactorGraph graph;
  Values values;
  values.insertPoint(L(0), Eigen::Vector3d::Zero());
  values.insertPoint(L(1), Eigen::Vector3d(1, 2, 3));
  for (int i = 0; i < 2; ++i) {
    graph.emplace<test::LinearFactor>(
        std::vector<Key>{L(0), L(1)},
        std::vector<Eigen::MatrixXd>{-Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd::Identity(3, 3)},
        Eigen::VectorXd(Eigen::Vector3d(1, 2, 3)), NoiseModel::isotropic(3, 0.1));
  }
  GraphProblem problem(graph, values);
  expectRankDeficient(problem, {L(1)});
  expectRankDeficient(problem, {L(0)});
}

TEST(LandmarkSchurCovariance, RejectsAReducedSystemAboveTheLimit) {
  // 3 334 poses with priors: 20 004 reduced degrees of freedom.
  FactorGraph graph;
  Values values;
  const int num_poses = internal::kLandmarkSchurMaxReducedDimension / 6 + 1;
  for (int k = 0; k < num_poses; ++k) {
    values.insertPose(X(k), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
    graph.emplace<test::TestPosePriorFactor>(X(k), SE3d(), NoiseModel::isotropic(6, 0.1));
  }
  GraphProblem problem(graph, values);
  try {
    jointMarginalCovariance(problem, {X(0)}, optionsFor(Algorithm::landmark_schur));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the reduced system has 20004 degrees of freedom"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("use the sparse_qr algorithm"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hsmap
