// Spline initialisation through the engine: SplinePoseFactors at several
// times per knot interval (exact poses of a known spline) plus a few
// SplineInsPositionFactors / SplineInsAttitudeFactors at off-grid fix times,
// solved from control points 0.2 m / ~6 deg off, must give back the known
// control points. (tests/factors does not link the solvers, hence here.)

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/se3_bspline.h"
#include "core/geometry/so3.h"
#include "factors/spline_ins_attitude_factor.h"
#include "factors/spline_ins_position_factor.h"
#include "factors/spline_pose_factor.h"
#include "factors/spline_timing.h"
#include "solvers/graph_solver.h"

namespace hsmap {
namespace {

SE3d randomPerturbation(std::mt19937& rng, double max_angle, double max_translation) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d omega(unit(rng), unit(rng), unit(rng));
  const Eigen::Vector3d t(unit(rng), unit(rng), unit(rng));
  return SE3d(expSO3(Eigen::Vector3d(omega * max_angle)), t * max_translation);
}

TEST(SplinePoseFactorRecovery, RecoversPerturbedControlPointsFromPosesAtSeveralTimes) {
  constexpr double kT0 = 3.0;
  constexpr double kDt = 0.1;
  constexpr int kNumControlPoints = 10;
  std::mt19937 rng(91);
  std::vector<SE3d> truth_points;
  for (int k = 0; k < kNumControlPoints; ++k) {
    const double t = kT0 + (k - 1) * kDt;
    truth_points.push_back(
        SE3d(expSO3(Eigen::Vector3d(0.2 * std::sin(3.0 * t), 0.1 * std::cos(2.0 * t), 0.3 * t)),
             Eigen::Vector3d(0.4 * t, 0.3 * std::sin(t), 10.0 + 0.1 * t)) *
        randomPerturbation(rng, 0.03, 0.02));
  }
  const SE3Splined truth(kT0, kDt, truth_points);
  const SplineTiming timing = SplineTiming::of(truth);
  const SE3d T_B_C(expSO3(Eigen::Vector3d(0.1, -0.2, 1.4)), Eigen::Vector3d(0.5, -0.1, 0.3));

  FactorGraph graph;
  const NoiseModel pose_noise = NoiseModel::fromSigmas(
      (Vector6d() << 0.02, 0.02, 0.02, 0.005, 0.005, 0.005).finished());
  int num_poses = 0;
  for (double t = truth.validBegin(); t <= truth.validEnd() + 1e-12; t += kDt / 4.0) {
    const double t_clamped = std::min(t, truth.validEnd());
    graph.emplace<SplinePoseFactor>(timing, t_clamped, truth.pose(t_clamped), pose_noise);
    ++num_poses;
  }
  EXPECT_EQ(num_poses, 4 * (kNumControlPoints - 3) + 1);
  for (const double t_fix : {3.013, 3.237, 3.481, 3.652}) {
    const SE3d T_W_B = truth.pose(t_fix) * T_B_C.inverse();
    graph.emplace<SplineInsPositionFactor>(timing, t_fix, T_W_B.t, T_B_C,
                                           NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 0.5, 0.05)));
    graph.emplace<SplineInsAttitudeFactor>(timing, t_fix, T_W_B.q, T_B_C,
                                           NoiseModel::isotropic(3, 0.01));
  }

  Values values;
  for (int j = 0; j < kNumControlPoints; ++j) {
    const SE3d start = truth_points[j] * randomPerturbation(rng, 0.06, 0.2);
    values.insertPose(S(j), start.q, start.t);
  }

  SolverOptions options;
  options.num_threads = 2;
  options.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-14;
  const SolveReport report = solve(graph, values, options);
  EXPECT_TRUE(report.usable) << report.toString();
  EXPECT_GT(report.initial_cost, 1e3) << report.toString();
  EXPECT_LT(report.final_cost, 1e-12) << report.toString();
  EXPECT_EQ(report.num_free_parameters, 6 * kNumControlPoints);
  EXPECT_EQ(report.by_factor_type.at("SplinePoseFactor").count, static_cast<std::size_t>(num_poses));

  for (int j = 0; j < kNumControlPoints; ++j) {
    const SE3d estimate(values.poseRotation(S(j)), values.poseTranslation(S(j)));
    const Vector6d error = (truth_points[j].inverse() * estimate).log();
    EXPECT_LT(error.head<3>().norm(), 1e-6) << "S(" << j << ")";
    EXPECT_LT(error.tail<3>().norm(), 1e-6) << "S(" << j << ")";
  }
}

}  // namespace
}  // namespace hsmap
