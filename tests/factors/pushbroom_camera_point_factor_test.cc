#include "factors/pushbroom_camera_point_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::residualAt;
using test::poseBlock;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;

constexpr double kT0 = 10.0;
constexpr double kDt = 0.2;
constexpr int kNumControlPoints = 12;

PushbroomParameters uhiCamera() {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = 1500.0;
  p.cx = 960.0;
  p.distortion = {0.02, -0.005};
  return p;
}

NoiseModel lineNoise() { return NoiseModel::fromSigmas(Eigen::Vector2d(0.5, 0.5 / 1500.0)); }

const SE3d kT_C_U(expSO3(Eigen::Vector3d(0.02, -0.03, 1.5)), Eigen::Vector3d(0.1, -0.02, 0.05));

SE3Splined trajectory(std::mt19937& rng) {
  std::vector<SE3d> control_points;
  for (int k = 0; k < kNumControlPoints; ++k) {
    const double t = kT0 + (k - 1) * kDt;
    const SE3d nominal(expSO3(Eigen::Vector3d(0.15 * std::sin(2.0 * t), 0.1 * std::cos(3.0 * t), 0.4 * t)),
                       Eigen::Vector3d(0.8 * t, 0.3 * std::sin(1.5 * t), 5.0 + 0.1 * t));
    control_points.push_back(nominal * test::randomPose(rng, 0.05, 0.03));
  }
  return SE3Splined(kT0, kDt, control_points);
}

std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline, int first, const SE3d& T_C_U, double d) {
  std::vector<test::ParameterBlock> blocks;
  for (int k = 0; k < PushbroomLineFactor::kNumControlPoints; ++k) {
    blocks.push_back(poseBlock(spline.controlPoints()[std::size_t(first + k)]));
  }
  blocks.push_back(poseBlock(T_C_U));
  blocks.push_back(scalarBlock(d));
  return blocks;
}

TEST(PushbroomCameraPointFactor, EqualsTheFixedPointLineFactorAtTheCarriedPoint) {
  std::mt19937 rng(5);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  const double t_recorded = kT0 + 4.3 * kDt, d0 = 0.02, d = 0.035;
  const double t_reference = t_recorded + d0 + 0.01;
  const Eigen::Vector3d p_C(0.3, -0.2, 2.4);
  const PushbroomCameraPointFactor factor(timing, d0, E(0), D(0), t_reference, p_C, {t_recorded, 700.0},
                                          uhiCamera(), lineNoise());
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(3), S(4), S(5), S(6), S(7), E(0), D(0)}));
  const Eigen::Vector3d p_W = spline.pose(t_reference) * p_C;
  const PushbroomLineFactor line(timing, d0, E(0), D(0), p_W, {t_recorded, 700.0}, uhiCamera(), lineNoise());
  ASSERT_EQ(line.firstControlPoint(), factor.firstControlPoint());
  const auto blocks = stateOf(spline, factor.firstControlPoint(), kT_C_U, d);
  EXPECT_TRUE(residualAt(*factor.createCostFunction(), blocks)
                  .isApprox(residualAt(*line.createCostFunction(), blocks), 1e-10));
}

TEST(PushbroomCameraPointFactor, IsBlindToARigidMotionOfTheWholeTrajectory) {
  // The point moves with the trajectory: moving every control point by G
  // leaves the residual unchanged (a fixed p_W would not be).
  std::mt19937 rng(6);
  const SE3Splined spline = trajectory(rng);
  const SE3d G(expSO3(Eigen::Vector3d(0.01, -0.02, 0.03)), Eigen::Vector3d(0.03, -0.025, 0.01));
  std::vector<SE3d> moved;
  for (const SE3d& T : spline.controlPoints()) moved.push_back(G * T);
  const SE3Splined moved_spline(kT0, kDt, moved);
  const SplineTiming timing = SplineTiming::of(spline);
  const double t_recorded = kT0 + 5.6 * kDt;
  const PushbroomCameraPointFactor factor(timing, 0.0, E(0), D(0), t_recorded, Eigen::Vector3d(-0.1, 0.3, 2.0),
                                          {t_recorded, 800.0}, uhiCamera(), lineNoise());
  const int j = factor.firstControlPoint();
  const Eigen::VectorXd before = residualAt(*factor.createCostFunction(), stateOf(spline, j, kT_C_U, 0.01));
  const Eigen::VectorXd after = residualAt(*factor.createCostFunction(), stateOf(moved_spline, j, kT_C_U, 0.01));
  EXPECT_TRUE(before.isApprox(after, 1e-9)) << before.transpose() << " vs " << after.transpose();
}

TEST(PushbroomCameraPointFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(7);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  for (const auto& [t_recorded, d] : std::vector<std::pair<double, double>>{
           {kT0 + 3.2 * kDt, 0.0}, {kT0 + 3.2 * kDt, 0.07}, {kT0 + 6.8 * kDt, -0.08}}) {
    const PushbroomCameraPointFactor factor(timing, 0.0, E(0), D(0), t_recorded + 0.02,
                                            Eigen::Vector3d(0.2, 0.1, 2.5), {t_recorded, 900.0},
                                            uhiCamera(), lineNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             stateOf(spline, factor.firstControlPoint(), kT_C_U, d)))
        << "t_recorded " << t_recorded << ", d " << d;
  }
}

Eigen::VectorXd intrinsicsOf(const PushbroomParameters& p) {
  Eigen::VectorXd k(PushbroomCamera::kNumIntrinsics);
  k << p.f, p.cx, p.distortion[0], p.distortion[1];
  return k;
}

TEST(PushbroomCameraPointFactor, SelfCalibratingFormEqualsTheFixedFormAtTheSameIntrinsics) {
  std::mt19937 rng(8);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  const double t_recorded = kT0 + 4.6 * kDt;
  const Eigen::Vector3d p_C(-0.4, 0.1, 2.2);
  const PushbroomCameraPointFactor fixed(timing, 0.0, E(0), D(0), t_recorded, p_C, {t_recorded, 300.0},
                                         uhiCamera(), lineNoise());
  const PushbroomCameraPointFactor calibrating(timing, 0.0, E(0), D(0), K(0), t_recorded, p_C,
                                               {t_recorded, 300.0}, uhiCamera(), lineNoise());
  EXPECT_TRUE(calibrating.estimatesIntrinsics());
  EXPECT_FALSE(fixed.estimatesIntrinsics());
  EXPECT_EQ(calibrating.keys().back(), K(0));
  EXPECT_EQ(calibrating.keys().size(), fixed.keys().size() + 1);
  auto blocks = stateOf(spline, fixed.firstControlPoint(), kT_C_U, 0.01);
  const Eigen::VectorXd r_fixed = residualAt(*fixed.createCostFunction(), blocks);
  blocks.push_back(test::vectorBlock(intrinsicsOf(uhiCamera())));
  EXPECT_TRUE(residualAt(*calibrating.createCostFunction(), blocks).isApprox(r_fixed, 1e-12));
  // Another focal length moves the predicted sample: the block is used.
  blocks.back().values[0] *= 1.01;
  EXPECT_GT(std::abs(residualAt(*calibrating.createCostFunction(), blocks)[0] - r_fixed[0]), 0.1);
}

TEST(PushbroomCameraPointFactor, SelfCalibratingJacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(9);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  Eigen::VectorXd k = intrinsicsOf(uhiCamera());
  k << 1512.0, 955.0, 0.035, -0.012;
  for (const auto& [t_recorded, d] : std::vector<std::pair<double, double>>{
           {kT0 + 3.2 * kDt, 0.0}, {kT0 + 6.8 * kDt, -0.08}}) {
    for (const Eigen::Vector3d& p_C : {Eigen::Vector3d(0.2, 0.1, 2.5), Eigen::Vector3d(-0.9, 0.05, 1.8)}) {
      const PushbroomCameraPointFactor factor(timing, 0.0, E(0), D(0), K(0), t_recorded + 0.02, p_C,
                                              {t_recorded, 900.0}, uhiCamera(), lineNoise());
      auto blocks = stateOf(spline, factor.firstControlPoint(), kT_C_U, d);
      blocks.push_back(test::vectorBlock(k));
      EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), blocks))
          << "t_recorded " << t_recorded << ", d " << d << ", p_C " << p_C.transpose();
    }
  }
}

TEST(PushbroomCameraPointFactor, RejectsAReferenceTimeOutsideItsWindow) {
  const SplineTiming timing{kT0, kDt, kNumControlPoints};
  const double t_recorded = kT0 + 4.3 * kDt;
  EXPECT_THROW(PushbroomCameraPointFactor(timing, 0.0, E(0), D(0), t_recorded + 0.5,
                                          Eigen::Vector3d(0, 0, 2), {t_recorded, 10.0}, uhiCamera(),
                                          lineNoise()),
               std::out_of_range);
  EXPECT_THROW(PushbroomCameraPointFactor(timing, 0.0, E(0), D(0), t_recorded,
                                          Eigen::Vector3d(0, NAN, 2), {t_recorded, 10.0}, uhiCamera(),
                                          lineNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
