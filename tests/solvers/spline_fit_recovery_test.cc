// Nonlinear recovery of a continuous-time trajectory: a uniform cubic SE(3)
// B-spline (0.1 s knots) fitted to noisy pose samples (50 Hz, 2 cm, 0.3 deg)
// of the known smooth motion of the synthetic transect, from control points
// 0.3 m / 5 deg off. The fitted spline must reproduce the motion within the
// noise: for a least-squares fit the mean variance of the fitted values at
// the samples is sigma^2 p / n (p parameters, n residuals: the trace of the
// hat matrix), and the actual RMS error must stay within 3x of that.
//
// The samples enter as SplinePoseFactors (factors/spline_pose_factor.h).

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/se3_bspline.h"
#include "factors/spline_pose_factor.h"
#include "factors/spline_timing.h"
#include "solvers/graph_solver.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {


TEST(SplineFitRecovery, RecoversASmoothMotionFromNoisyPoseSamples) {
  constexpr double kDeg = M_PI / 180.0;
  constexpr double kSigmaPosition = 0.02;
  constexpr double kSigmaRotation = 0.3 * kDeg;
  test::TransectConfig config;
  config.dynamics = 2.0;
  const SE3d T_B_C = test::cameraOnBody();
  auto motion = [&](double t) { return test::vehicleMotion(config, t) * T_B_C; };

  const double duration = 10.0;
  const SE3Splined shape = test::truthSpline(config, T_B_C, 0.0, duration);
  const SplineTiming timing = SplineTiming::of(shape);
  ASSERT_EQ(timing.num_control_points, 103);

  std::mt19937 rng(8);
  FactorGraph graph;
  const NoiseModel noise = NoiseModel::fromSigmas(
      (Vector6d() << Eigen::Vector3d::Constant(kSigmaPosition),
       Eigen::Vector3d::Constant(kSigmaRotation))
          .finished());
  std::vector<double> sample_times;
  for (int k = 0; k <= 500; ++k) sample_times.push_back(std::min(k * 0.02, duration));
  for (const double t : sample_times) {
    const SE3d measured = motion(t) * SE3d::exp(test::gaussian6(rng, kSigmaPosition, kSigmaRotation));
    graph.emplace<SplinePoseFactor>(timing, t, measured, noise);
  }
  Values values;
  for (int j = 0; j < timing.num_control_points; ++j) {
    const SE3d start = shape.controlPoints()[j] * SE3d::exp(test::gaussian6(rng, 0.3, 5.0 * kDeg));
    values.insertPose(S(j), start.q, start.t);
  }

  auto rmsErrors = [&](const Values& estimate) {
    std::vector<SE3d> control_points;
    for (int j = 0; j < timing.num_control_points; ++j) {
      control_points.emplace_back(estimate.poseRotation(S(j)), estimate.poseTranslation(S(j)));
    }
    const SE3Splined fitted(timing.t0, timing.dt, control_points);
    double position = 0.0, rotation = 0.0;
    for (const double t : sample_times) {
      const Vector6d xi = (motion(t).inverse() * fitted.pose(t)).log();
      position += xi.head<3>().squaredNorm();
      rotation += xi.tail<3>().squaredNorm();
    }
    return std::make_pair(std::sqrt(position / sample_times.size()),
                          std::sqrt(rotation / sample_times.size()));
  };
  const auto [start_position, start_rotation] = rmsErrors(values);

  SolverOptions options;
  options.num_threads = 2;
  options.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  const SolveReport report = solve(graph, values, options);
  EXPECT_TRUE(report.converged) << report.toString();
  EXPECT_EQ(report.num_free_parameters, 6 * 103);

  const auto [position, rotation] = rmsErrors(values);
  // Mean variance of the fitted values: sigma^2 p / n per component.
  const double p_over_n = static_cast<double>(report.num_free_parameters) / report.num_residuals;
  const double expected_position = std::sqrt(3.0 * kSigmaPosition * kSigmaPosition * p_over_n);
  const double expected_rotation = std::sqrt(3.0 * kSigmaRotation * kSigmaRotation * p_over_n);
  std::printf("spline fit: position %.4f m (expected %.4f), rotation %.5f rad (expected %.5f)\n",
              position, expected_position, rotation, expected_rotation);
  EXPECT_GT(start_position, 10.0 * expected_position);
  EXPECT_GT(start_rotation, 10.0 * expected_rotation);
  EXPECT_LT(position, 3.0 * expected_position);
  EXPECT_LT(rotation, 3.0 * expected_rotation);
  // The fit averages the noise down: better than a single sample.
  EXPECT_LT(position, std::sqrt(3.0) * kSigmaPosition);
  EXPECT_LT(rotation, std::sqrt(3.0) * kSigmaRotation);
}

}  // namespace
}  // namespace hsmap
