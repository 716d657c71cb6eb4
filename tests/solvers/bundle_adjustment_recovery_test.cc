// Nonlinear recovery with the real factors: keyframe bundle adjustment with
// INS position/attitude factors on a synthetic transect (20 keyframes, 500
// landmarks, 0.5 px pixel noise, INS noise) solved from a start 0.2 m / 2 deg
// / 0.2 m off the truth. The error after the solve is compared with what the
// noise allows: the engine's own marginal covariances at the optimum give the
// expected RMS error of every variable, and the actual RMS error must stay
// within 3x of it. A second test injects gross outliers and checks that the
// robust loss keeps the solution within the same bounds while the plain
// least-squares solution is dragged away.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

struct Errors {
  double position_rms_m = 0.0;
  double rotation_rms_rad = 0.0;
  double landmark_rms_m = 0.0;
};

Errors errorsOf(const test::Transect& transect, const Values& values) {
  Errors errors;
  const std::size_t n = transect.T_W_C.size();
  for (std::size_t k = 0; k < n; ++k) {
    const SE3d estimate(values.poseRotation(X(k)), values.poseTranslation(X(k)));
    const Vector6d xi = (transect.T_W_C[k].inverse() * estimate).log();
    errors.position_rms_m += xi.head<3>().squaredNorm();
    errors.rotation_rms_rad += xi.tail<3>().squaredNorm();
  }
  for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
    errors.landmark_rms_m += (values.point(L(i)) - transect.p_W[i]).squaredNorm();
  }
  errors.position_rms_m = std::sqrt(errors.position_rms_m / n);
  errors.rotation_rms_rad = std::sqrt(errors.rotation_rms_rad / n);
  errors.landmark_rms_m = std::sqrt(errors.landmark_rms_m / transect.p_W.size());
  return errors;
}

// Expected RMS errors: sqrt of the mean trace of the marginal covariances
// (pose blocks split into translation rho and rotation phi).
Errors expectedErrors(GraphProblem& problem, const test::Transect& transect) {
  std::vector<Key> keys;
  for (std::size_t k = 0; k < transect.T_W_C.size(); ++k) keys.push_back(X(k));
  for (std::size_t i = 0; i < transect.p_W.size(); ++i) keys.push_back(L(i));
  CovarianceOptions options;
  options.num_threads = 2;
  const std::map<Key, Eigen::MatrixXd> covariances = marginalCovariances(problem, keys, options);
  Errors expected;
  for (std::size_t k = 0; k < transect.T_W_C.size(); ++k) {
    const Eigen::MatrixXd& covariance = covariances.at(X(k));
    expected.position_rms_m += covariance.topLeftCorner<3, 3>().trace();
    expected.rotation_rms_rad += covariance.bottomRightCorner<3, 3>().trace();
  }
  for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
    expected.landmark_rms_m += covariances.at(L(i)).trace();
  }
  expected.position_rms_m = std::sqrt(expected.position_rms_m / transect.T_W_C.size());
  expected.rotation_rms_rad = std::sqrt(expected.rotation_rms_rad / transect.T_W_C.size());
  expected.landmark_rms_m = std::sqrt(expected.landmark_rms_m / transect.p_W.size());
  return expected;
}

SolverOptions testOptions() {
  SolverOptions options;
  options.num_threads = 2;
  return options;
}

// The clean problem, solved once; its covariance sets the expected errors
// for every test of this file.
class BundleAdjustmentRecoveryTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    test::TransectConfig config;
    config.seed = 42;
    transect_ = new test::Transect(test::makeTransect(config));
    FactorGraph graph;
    values_ = new Values();
    test::buildBundleAdjustment(*transect_, RobustLoss::none(), &graph, values_);
    start_ = new Errors(errorsOf(*transect_, *values_));
    GraphProblem problem(graph, *values_);
    report_ = new SolveReport(solve(problem, testOptions()));
    expected_ = new Errors(expectedErrors(problem, *transect_));
  }
  static void TearDownTestSuite() {
    delete transect_;
    delete values_;
    delete start_;
    delete report_;
    delete expected_;
  }

  static test::Transect* transect_;
  static Values* values_;
  static Errors* start_;
  static SolveReport* report_;
  static Errors* expected_;
};

test::Transect* BundleAdjustmentRecoveryTest::transect_ = nullptr;
Values* BundleAdjustmentRecoveryTest::values_ = nullptr;
Errors* BundleAdjustmentRecoveryTest::start_ = nullptr;
SolveReport* BundleAdjustmentRecoveryTest::report_ = nullptr;
Errors* BundleAdjustmentRecoveryTest::expected_ = nullptr;

TEST_F(BundleAdjustmentRecoveryTest, SceneHasTheIntendedSize) {
  EXPECT_EQ(transect_->T_W_C.size(), 20u);
  EXPECT_EQ(transect_->p_W.size(), 500u);
  // Every landmark is seen several times (3 m altitude, 0.5 m between keyframes).
  EXPECT_GT(transect_->observations.size(), 4u * 500u);
  EXPECT_EQ(report_->by_factor_type.at("ReprojectionFactor").count, transect_->observations.size());
  EXPECT_EQ(report_->by_factor_type.at("InsPositionFactor").count, 20u);
  EXPECT_EQ(report_->by_factor_type.at("InsAttitudeFactor").count, 20u);
  EXPECT_EQ(report_->num_eliminated_landmarks, 500u);
}

TEST_F(BundleAdjustmentRecoveryTest, RecoversTheTruthWithinTheNoise) {
  EXPECT_TRUE(report_->converged) << report_->toString();
  EXPECT_EQ(report_->linear_solver, "SPARSE_SCHUR (SuiteSparse)");
  // The start is far outside the noise...
  EXPECT_GT(start_->position_rms_m, 10.0 * expected_->position_rms_m);
  EXPECT_GT(start_->landmark_rms_m, 10.0 * expected_->landmark_rms_m);
  // ...and the solution within 3x the error the noise allows.
  const Errors errors = errorsOf(*transect_, *values_);
  std::printf("errors / expected: position %.4f / %.4f m, rotation %.5f / %.5f rad, landmarks %.4f / %.4f m\n",
              errors.position_rms_m, expected_->position_rms_m, errors.rotation_rms_rad,
              expected_->rotation_rms_rad, errors.landmark_rms_m, expected_->landmark_rms_m);
  EXPECT_LT(errors.position_rms_m, 3.0 * expected_->position_rms_m)
      << "expected " << expected_->position_rms_m;
  EXPECT_LT(errors.rotation_rms_rad, 3.0 * expected_->rotation_rms_rad)
      << "expected " << expected_->rotation_rms_rad;
  EXPECT_LT(errors.landmark_rms_m, 3.0 * expected_->landmark_rms_m)
      << "expected " << expected_->landmark_rms_m;
  // The expected errors themselves are plausible: no worse than the INS alone.
  EXPECT_LT(expected_->position_rms_m, std::sqrt(2 * 0.05 * 0.05 + 0.02 * 0.02));
  EXPECT_LT(expected_->rotation_rms_rad, 0.5 * M_PI / 180.0);
}

TEST_F(BundleAdjustmentRecoveryTest, FinalCostMatchesTheNoiseLevel) {
  // At the optimum 2 * cost ~ chi^2 with (residuals - free parameters) dof.
  const double dof = report_->num_residuals - report_->num_free_parameters;
  const double chi2 = 2.0 * report_->final_cost;
  EXPECT_NEAR(chi2 / dof, 1.0, 5.0 * std::sqrt(2.0 / dof)) << report_->toString();
}

// Gross outliers (3% of the pixels, uniform over the image) on the same scene.
struct OutlierRun {
  Errors errors;
  SolveReport report;
  std::size_t outliers = 0;
  std::size_t inliers = 0;
};

OutlierRun solveWithOutliers(RobustLoss loss) {
  test::TransectConfig config;
  config.seed = 42;
  config.outlier_fraction = 0.03;
  const test::Transect transect = test::makeTransect(config);
  FactorGraph graph;
  Values values;
  test::buildBundleAdjustment(transect, loss, &graph, &values);
  OutlierRun run;
  run.report = solve(graph, values, testOptions());
  run.errors = errorsOf(transect, values);
  for (const auto& observation : transect.observations) {
    (observation.outlier ? run.outliers : run.inliers) += 1;
  }
  return run;
}

TEST_F(BundleAdjustmentRecoveryTest, RobustLossSuppressesInjectedOutliers) {
  const OutlierRun robust = solveWithOutliers(RobustLoss::cauchy(3.0));
  ASSERT_GT(robust.outliers, 50u);
  EXPECT_TRUE(robust.report.usable) << robust.report.toString();
  EXPECT_LT(robust.errors.position_rms_m, 3.0 * expected_->position_rms_m);
  EXPECT_LT(robust.errors.rotation_rms_rad, 3.0 * expected_->rotation_rms_rad);
  EXPECT_LT(robust.errors.landmark_rms_m, 3.0 * expected_->landmark_rms_m);
  // The report counts the outliers: every injected one is beyond the loss
  // scale (3 sigmas), plus the inliers' 2-D Gaussian tail exp(-9/2) ~ 1.1%.
  std::printf("robust: %.4f m, %.5f rad, %.4f m; outliers %zu, inliers %zu\n",
              robust.errors.position_rms_m, robust.errors.rotation_rms_rad,
              robust.errors.landmark_rms_m, robust.outliers, robust.inliers);
  const std::size_t beyond =
      robust.report.by_factor_type.at("ReprojectionFactor").final_beyond_loss_scale;
  EXPECT_GE(beyond, robust.outliers * 95 / 100);
  EXPECT_LE(beyond, robust.outliers + robust.inliers * 3 / 100);

  // Without the robust loss the same data pulls the landmarks away: the test
  // above would notice a loss that did nothing.
  const OutlierRun plain = solveWithOutliers(RobustLoss::none());
  std::printf("plain: %.4f m, %.5f rad, %.4f m\n", plain.errors.position_rms_m,
              plain.errors.rotation_rms_rad, plain.errors.landmark_rms_m);
  EXPECT_GT(plain.errors.landmark_rms_m, 3.0 * expected_->landmark_rms_m);
  EXPECT_GT(plain.errors.landmark_rms_m, 3.0 * robust.errors.landmark_rms_m);
}

}  // namespace
}  // namespace hsmap
