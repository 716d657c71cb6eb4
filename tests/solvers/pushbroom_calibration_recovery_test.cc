// Nonlinear recovery of the UHI calibration: the RGB-UHI extrinsic T_C_U and
// the UHI time offset d from push-broom observations of known 3D points
// (PushbroomLineFactor, fixed-point form), with the true camera trajectory
// spline held constant. Start: 2 deg, 5 cm and 15 ms off. The result must be
// well within those (10x better) and consistent with the engine's own
// marginal covariance (Mahalanobis distance of the 7-dof error below the
// chi-square 99.9% quantile).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "factors/pushbroom_line_factor.h"
#include "factors/spline_timing.h"
#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

TEST(PushbroomCalibrationRecovery, RecoversExtrinsicAndTimeOffsetFromScanLines) {
  constexpr double kDeg = M_PI / 180.0;
  constexpr double kTrueOffset = 0.015;
  constexpr double kSigmaU = 0.3;
  test::TransectConfig config;
  config.dynamics = 2.0;  // rolling and pitching make d distinguishable from T_C_U
  const SE3d T_B_C = test::cameraOnBody();
  const SE3Splined spline = test::truthSpline(config, T_B_C, 0.0, 10.0);
  const SplineTiming timing = SplineTiming::of(spline);
  const PushbroomParameters camera = test::uhiCamera();
  const SE3d T_C_U_true = test::uhiOnCamera();

  std::vector<double> line_times;
  for (int k = 0; k < 270; ++k) line_times.push_back(0.5 + k / 30.0);
  std::mt19937 rng(17);
  const auto observations = test::makePushbroomObservations(
      spline, T_C_U_true, kTrueOffset, camera, line_times, 16, kSigmaU, config.altitude_m, rng);
  ASSERT_EQ(observations.size(), 270u * 16u);

  // Start 2 deg, 5 cm and 15 ms away from the truth.
  const Eigen::Vector3d rotation_axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const Eigen::Vector3d translation_direction = Eigen::Vector3d(-0.3, 1.0, 0.8).normalized();
  const SE3d T_C_U_start(T_C_U_true.q * expSO3(Eigen::Vector3d(2.0 * kDeg * rotation_axis)),
                         T_C_U_true.t + 0.05 * translation_direction);
  const double d_start = kTrueOffset + 0.015;

  FactorGraph graph;
  const NoiseModel noise =
      NoiseModel::fromSigmas(Eigen::Vector2d(kSigmaU, test::acrossLineSigma(camera)));
  for (const auto& observation : observations) {
    graph.emplace<PushbroomLineFactor>(timing, d_start, E(0), D(0), observation.p_W,
                                       observation.observation, camera, noise);
  }
  Values values;
  GraphProblemOptions problem_options;
  for (int j = 0; j < timing.num_control_points; ++j) {
    values.insertPose(S(j), spline.controlPoints()[j].q, spline.controlPoints()[j].t);
    problem_options.constant.insert(S(j));
  }
  values.insertPose(E(0), T_C_U_start.q, T_C_U_start.t);
  values.insertScalar(D(0), d_start);

  GraphProblem problem(graph, values, problem_options);
  SolverOptions options;
  options.num_threads = 2;
  options.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  const SolveReport report = solve(problem, options);
  EXPECT_TRUE(report.converged) << report.toString();
  EXPECT_EQ(report.num_free_parameters, 7);

  const SE3d T_C_U(values.poseRotation(E(0)), values.poseTranslation(E(0)));
  const double d = values.scalar(D(0));
  const Vector6d xi = (T_C_U_true.inverse() * T_C_U).log();
  const double rotation_error = logSO3(T_C_U_true.q.conjugate() * T_C_U.q).norm();
  const double translation_error = (T_C_U.t - T_C_U_true.t).norm();
  const double offset_error = std::abs(d - kTrueOffset);
  std::printf("T_C_U: %.4f deg, %.5f m; d: %.3f ms off\n", rotation_error / kDeg,
              translation_error, 1e3 * offset_error);
  EXPECT_LT(rotation_error, 0.2 * kDeg);
  EXPECT_LT(translation_error, 0.005);
  EXPECT_LT(offset_error, 0.0015);

  // Consistency with the noise: the error's Mahalanobis distance under the
  // joint marginal covariance of [T_C_U (rho, phi); d].
  const Eigen::MatrixXd covariance = jointMarginalCovariance(problem, {E(0), D(0)});
  ASSERT_EQ(covariance.rows(), 7);
  Eigen::VectorXd error(7);
  error << xi, d - kTrueOffset;
  const double mahalanobis2 = error.dot(covariance.ldlt().solve(error));
  std::printf("sigmas: rot %.4f deg, trans %.5f m, d %.3f ms; Mahalanobis^2 %.2f\n",
              std::sqrt(covariance.block<3, 3>(3, 3).trace()) / kDeg,
              std::sqrt(covariance.block<3, 3>(0, 0).trace()), 1e3 * std::sqrt(covariance(6, 6)),
              mahalanobis2);
  EXPECT_LT(mahalanobis2, 24.3);  // chi-square, 7 dof, 99.9%

  // The factors' control-point windows still cover the final offset.
  const auto* factor = dynamic_cast<const PushbroomLineFactor*>(graph.factor(0).get());
  ASSERT_NE(factor, nullptr);
  EXPECT_TRUE(factor->coversTimeOffset(d));
}

}  // namespace
}  // namespace hsmap
