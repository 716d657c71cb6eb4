#include "factors/pushbroom_line_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "tests/factors/factor_test_support.h"
#include "tests/factors/reference_jacobians.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;
using test::vectorBlock;

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

PushbroomParameters undistortedUhiCamera() {
  PushbroomParameters p = uhiCamera();
  p.distortion = {0.0, 0.0};
  return p;
}

NoiseModel lineNoise() { return NoiseModel::fromSigmas(Eigen::Vector2d(0.5, 0.5 / 1500.0)); }

SE3d extrinsic() {
  return SE3d(expSO3(Eigen::Vector3d(0.02, -0.03, 1.5)), Eigen::Vector3d(0.1, -0.02, 0.05));
}

// Downward-looking survey motion with turns and wobble, perturbed per control point.
SE3Splined trajectory(std::mt19937& rng) {
  std::vector<SE3d> control_points;
  for (int k = 0; k < kNumControlPoints; ++k) {
    const double t = kT0 + (k - 1) * kDt;
    const SE3d nominal(expSO3(Eigen::Vector3d(0.15 * std::sin(2.0 * t), 0.1 * std::cos(3.0 * t),
                                              0.4 * t)),
                       Eigen::Vector3d(0.8 * t, 0.3 * std::sin(1.5 * t), 5.0 + 0.1 * t));
    control_points.push_back(nominal * test::randomPose(rng, 0.05, 0.03));
  }
  return SE3Splined(kT0, kDt, control_points);
}

// The state [S(j..j+4), T_C_U, d, (p_W)] of a factor.
std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline,
                                          const PushbroomLineFactor& factor, const SE3d& T_C_U,
                                          double d, const Eigen::Vector3d* p_W) {
  std::vector<test::ParameterBlock> blocks;
  for (int k = 0; k < PushbroomLineFactor::kNumControlPoints; ++k) {
    blocks.push_back(poseBlock(spline.controlPoints()[factor.firstControlPoint() + k]));
  }
  blocks.push_back(poseBlock(T_C_U));
  blocks.push_back(scalarBlock(d));
  if (p_W != nullptr) blocks.push_back(vectorBlock(*p_W));
  return blocks;
}

// A point seen exactly by pixel column x_U / z_U of the line exposed at t.
struct LineSighting {
  Eigen::Vector3d p_W;
  double u;
};

LineSighting sightingAt(const SE3Splined& spline, double t, const SE3d& T_C_U, double x_U,
                        double z_U) {
  const SE3d T_W_U = spline.pose(t) * T_C_U;
  const Eigen::Vector3d p_U(x_U, 0.0, z_U);
  return {T_W_U * p_U, PushbroomCamera(uhiCamera()).project(p_U).x()};
}

TEST(PushbroomLineFactor, WindowSpansTwoSegmentsAroundTheInitialExposureTime) {
  const SplineTiming timing{kT0, kDt, kNumControlPoints};
  const auto keysFor = [&](double t_recorded, double d0) {
    return PushbroomLineFactor(timing, d0, E(0), D(0), L(4), {t_recorded, 100.0}, uhiCamera(),
                               lineNoise());
  };
  // s = 3.3: segment 3 early (u < 0.5), so the window also covers segment 2.
  const PushbroomLineFactor early = keysFor(kT0 + 3.3 * kDt - 0.01, 0.01);
  EXPECT_EQ(early.name(), "PushbroomLineFactor");
  EXPECT_EQ(early.keys(),
            (std::vector<Key>{S(2), S(3), S(4), S(5), S(6), E(0), D(0), L(4)}));
  EXPECT_EQ(early.firstControlPoint(), 2);
  EXPECT_NEAR(early.coveredTimeRange().first, kT0 + 2.0 * kDt, 1e-12);
  EXPECT_NEAR(early.coveredTimeRange().second, kT0 + 4.0 * kDt, 1e-12);
  // s = 3.7: late in segment 3, so the window covers segments 3 and 4.
  EXPECT_EQ(keysFor(kT0 + 3.7 * kDt, 0.0).firstControlPoint(), 3);
  // Clamped at both ends of the spline.
  EXPECT_EQ(keysFor(kT0 + 0.2 * kDt, 0.0).firstControlPoint(), 0);
  EXPECT_EQ(keysFor(kT0 + (kNumControlPoints - 3) * kDt, 0.0).firstControlPoint(),
            kNumControlPoints - 5);
  // At least half a knot interval of margin on both sides of d0.
  EXPECT_TRUE(early.coversTimeOffset(0.01 + 0.5 * kDt));
  EXPECT_TRUE(early.coversTimeOffset(0.01 - 0.5 * kDt));
  EXPECT_FALSE(early.coversTimeOffset(0.01 + 0.8 * kDt));
  EXPECT_FALSE(early.coversTimeOffset(0.01 - 1.4 * kDt));
}

TEST(PushbroomLineFactor, FixedPointFormHasNoLandmarkKey) {
  const SplineTiming timing{kT0, kDt, kNumControlPoints};
  const PushbroomLineFactor factor(timing, 0.0, E(1), D(2), Eigen::Vector3d(1.0, 2.0, 3.0),
                                   {kT0 + 5.6 * kDt, 10.0}, uhiCamera(), lineNoise(),
                                   RobustLoss::huber(2.0));
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(5), S(6), S(7), S(8), S(9), E(1), D(2)}));
  EXPECT_FALSE(factor.hasLandmark());
  ASSERT_TRUE(factor.fixedPoint().has_value());
  EXPECT_EQ(*factor.fixedPoint(), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7, 7, 7, 7, 1}));
  EXPECT_EQ(factor.robustLoss().toString(), "huber(2)");
}

TEST(PushbroomLineFactor, ResidualAndTimeDerivativeMatchHandComputedValues) {
  // Straight-line spline S(j) = (I, (0.5 j, 0, 0)), t0 = 0, dt = 1: the
  // camera is at x = 0.5 (s + 1), moving at 0.5 m/s. Line recorded at 2.0,
  // d = 0.25: s = 2.25, camera at 1.625, U (T_C_U = (I, (0.1, 0, 0))) at 1.725.
  // p_W = (1.925, 0.01, 2): p_U = (0.2, 0.01, 2), u = 1500 * 0.1 + 960 = 1110,
  // y_U / z_U = 0.005. Measured u = 1100: r = (10, 0.005).
  // d r_u / d d = f * d(x_U / z_U)/dd = 1500 * (-0.5 / 2) = -375.
  const SplineTiming timing{0.0, 1.0, 8};
  const PushbroomLineFactor factor(timing, 0.25, E(0), D(0), L(0), {2.0, 1100.0},
                                   undistortedUhiCamera(), lineNoise());
  std::vector<test::ParameterBlock> blocks;
  for (int k = 0; k < 5; ++k) {
    const int j = factor.firstControlPoint() + k;
    blocks.push_back(poseBlock(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5 * j, 0, 0))));
  }
  blocks.push_back(poseBlock(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0, 0))));
  blocks.push_back(scalarBlock(0.25));
  blocks.push_back(vectorBlock(Eigen::Vector3d(1.925, 0.01, 2.0)));
  const auto evaluation = evaluate(*factor.createCostFunction(), blocks);
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 10.0, 1e-9);
  EXPECT_NEAR(evaluation.residual[1], 0.005, 1e-12);
  EXPECT_NEAR(evaluation.jacobians[6](0, 0), -375.0, 1e-9);
  EXPECT_NEAR(evaluation.jacobians[6](1, 0), 0.0, 1e-12);
}

TEST(PushbroomLineFactor, ResidualIsZeroAtTheTrueStateInBothForms) {
  std::mt19937 rng(81);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  const double d = 0.015;
  for (int trial = 0; trial < 10; ++trial) {
    const double t_recorded = std::uniform_real_distribution<double>(
        spline.validBegin() + 0.05, spline.validEnd() - 0.05)(rng);
    const double x_U = std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
    const LineSighting sighting = sightingAt(spline, t_recorded + d, extrinsic(), x_U, 4.0);
    const PushbroomLineFactor with_landmark(timing, d, E(0), D(0), L(0),
                                            {t_recorded, sighting.u}, uhiCamera(), lineNoise());
    const PushbroomLineFactor with_fixed_point(timing, d, E(0), D(0), sighting.p_W,
                                               {t_recorded, sighting.u}, uhiCamera(), lineNoise());
    EXPECT_LT(evaluate(*with_landmark.createCostFunction(),
                       stateOf(spline, with_landmark, extrinsic(), d, &sighting.p_W))
                  .residual.norm(),
              1e-8)
        << "trial " << trial;
    EXPECT_LT(evaluate(*with_fixed_point.createCostFunction(),
                       stateOf(spline, with_fixed_point, extrinsic(), d, nullptr))
                  .residual.norm(),
              1e-8)
        << "trial " << trial;
  }
}

TEST(PushbroomLineFactor, JacobiansMatchNumericTangentDifferencesInBothSegmentsOfTheWindow) {
  std::mt19937 rng(82);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  const double d0 = 0.02;
  // Recorded times early and late in segments, and the current d moved from
  // d0 so that the evaluation falls in the window's first or second segment.
  const std::vector<std::pair<double, double>> cases = {
      {kT0 + 3.2 * kDt, 0.0}, {kT0 + 3.2 * kDt, -0.3 * kDt}, {kT0 + 3.2 * kDt, 0.4 * kDt},
      {kT0 + 6.8 * kDt, 0.0}, {kT0 + 6.8 * kDt, 0.35 * kDt}, {kT0 + 6.8 * kDt, -0.45 * kDt},
      {kT0 + 0.1 * kDt, 0.2 * kDt}, {kT0 + 8.9 * kDt, -0.1 * kDt}};
  for (const auto& [t_recorded, d_shift] : cases) {
    const double d = d0 + d_shift;
    const LineSighting sighting = sightingAt(spline, t_recorded + d, extrinsic(), 0.3, 3.5);
    // Observed a few pixels and a fraction of the field of view off.
    const Eigen::Vector3d p_W = sighting.p_W + Eigen::Vector3d(0.02, -0.03, 0.01);
    const PushbroomLineFactor with_landmark(timing, d0, E(0), D(0), L(0),
                                            {t_recorded, sighting.u + 4.0}, uhiCamera(),
                                            lineNoise());
    ASSERT_TRUE(with_landmark.coversTimeOffset(d));
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*with_landmark.createCostFunction(),
                                             stateOf(spline, with_landmark, extrinsic(), d, &p_W)))
        << "t_recorded " << t_recorded << ", d " << d;
    const PushbroomLineFactor with_fixed_point(timing, d0, E(0), D(0), p_W,
                                               {t_recorded, sighting.u + 4.0}, uhiCamera(),
                                               lineNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*with_fixed_point.createCostFunction(),
                                             stateOf(spline, with_fixed_point, extrinsic(), d, nullptr)))
        << "t_recorded " << t_recorded << ", d " << d;
  }
}

TEST(PushbroomLineFactor, AnalyticJacobiansEqualTheAutodiffOnesInBothFormsAndSegments) {
  std::mt19937 rng(85);
  const SE3Splined spline = trajectory(rng);
  const SplineTiming timing = SplineTiming::of(spline);
  const double d0 = 0.02;
  for (int trial = 0; trial < 20; ++trial) {
    const double t_recorded = std::uniform_real_distribution<double>(
        spline.validBegin() + 0.05, spline.validEnd() - 0.05)(rng);
    // d anywhere in the window's margin, so either of its segments is current.
    const double d = d0 + std::uniform_real_distribution<double>(-0.45, 0.45)(rng) * kDt;
    const double x_U = std::uniform_real_distribution<double>(-0.6, 0.6)(rng);
    const LineSighting sighting = sightingAt(spline, t_recorded + d, extrinsic(), x_U, 3.5);
    const Eigen::Vector3d p_W =
        sighting.p_W + test::randomVector(rng, Eigen::Vector3d::Constant(-0.05),
                                          Eigen::Vector3d::Constant(0.05));
    const PushbroomObservation observation{t_recorded, sighting.u + 3.0};
    const PushbroomLineFactor with_landmark(timing, d0, E(0), D(0), L(0), observation, uhiCamera(),
                                            lineNoise());
    if (!with_landmark.coversTimeOffset(d)) continue;  // only near the spline's ends
    EXPECT_TRUE(test::tangentJacobiansMatchReference(
        *with_landmark.createCostFunction(), *with_landmark.createAutoDiffCostFunction(),
        stateOf(spline, with_landmark, extrinsic(), d, &p_W)))
        << "t_recorded " << t_recorded << ", d " << d;
    const PushbroomLineFactor with_fixed_point(timing, d0, E(0), D(0), p_W, observation,
                                               uhiCamera(), lineNoise());
    EXPECT_TRUE(test::tangentJacobiansMatchReference(
        *with_fixed_point.createCostFunction(), *with_fixed_point.createAutoDiffCostFunction(),
        stateOf(spline, with_fixed_point, extrinsic(), d, nullptr)))
        << "t_recorded " << t_recorded << ", d " << d;
  }
}

TEST(PushbroomLineFactor, AnalyticJacobiansHoldBehindTheCameraWhereTheDepthIsFloored) {
  std::mt19937 rng(86);
  const SE3Splined spline = trajectory(rng);
  const double t_recorded = kT0 + 5.4 * kDt;
  for (const double z_U : {0.009, 0.0, -0.4}) {
    const Eigen::Vector3d p_W =
        spline.pose(t_recorded) * extrinsic() * Eigen::Vector3d(0.003, 0.001, z_U);
    const PushbroomLineFactor factor(SplineTiming::of(spline), 0.0, E(0), D(0), L(0),
                                     {t_recorded, 1000.0}, uhiCamera(), lineNoise());
    const auto blocks = stateOf(spline, factor, extrinsic(), 0.0, &p_W);
    EXPECT_TRUE(test::tangentJacobiansMatchReference(*factor.createCostFunction(),
                                                     *factor.createAutoDiffCostFunction(), blocks))
        << "z_U " << z_U;
    // Far behind the camera the residual (~1e9) curves too sharply for the
    // h = 1e-4 difference quotient; near the floor it is still a fair reference.
    if (z_U >= 0.0) {
      EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), blocks))
          << "z_U " << z_U;
    }
  }
}

TEST(PushbroomLineFactor, JacobiansOfSomeBlocksOnlyEqualThoseOfAFullEvaluation) {
  // Ceres passes null for the Jacobians of constant blocks (e.g. a fixed T_C_U or d).
  std::mt19937 rng(87);
  const SE3Splined spline = trajectory(rng);
  const double t_recorded = kT0 + 4.3 * kDt;
  const LineSighting sighting = sightingAt(spline, t_recorded, extrinsic(), 0.2, 3.0);
  const PushbroomLineFactor factor(SplineTiming::of(spline), 0.0, E(0), D(0), L(0),
                                   {t_recorded, sighting.u + 2.0}, uhiCamera(), lineNoise());
  const auto blocks = stateOf(spline, factor, extrinsic(), 0.0, &sighting.p_W);
  const auto cost = factor.createCostFunction();
  EXPECT_TRUE(test::partialJacobiansMatchFull(
      *cost, blocks, {true, true, true, true, true, false, false, true}));
  EXPECT_TRUE(test::partialJacobiansMatchFull(
      *cost, blocks, {false, false, false, false, false, true, true, false}));
  EXPECT_TRUE(test::partialJacobiansMatchFull(
      *cost, blocks, {true, false, false, false, true, false, true, false}));
}

TEST(PushbroomLineFactor, ControlPointOutsideTheCurrentSegmentHasZeroJacobian) {
  std::mt19937 rng(83);
  const SE3Splined spline = trajectory(rng);
  const double t_recorded = kT0 + 4.3 * kDt;  // window S(3..7); segment 4 is its second
  const LineSighting sighting = sightingAt(spline, t_recorded, extrinsic(), 0.1, 3.0);
  const PushbroomLineFactor factor(SplineTiming::of(spline), 0.0, E(0), D(0), L(0),
                                   {t_recorded, sighting.u + 2.0}, uhiCamera(), lineNoise());
  ASSERT_EQ(factor.firstControlPoint(), 3);
  const auto evaluation =
      evaluate(*factor.createCostFunction(), stateOf(spline, factor, extrinsic(), 0.0, &sighting.p_W));
  EXPECT_TRUE(evaluation.jacobians[0].isZero(0.0));  // S(3) is not active in segment 4
  EXPECT_FALSE(evaluation.jacobians[4].isZero(0.0));
}

TEST(PushbroomLineFactor, ResidualIsSmoothAcrossTheKnotInsideTheWindow) {
  std::mt19937 rng(84);
  const SE3Splined spline = trajectory(rng);
  const double t_recorded = kT0 + 5.0 * kDt;  // the knot between the window's segments
  const LineSighting sighting = sightingAt(spline, t_recorded, extrinsic(), -0.2, 3.0);
  const PushbroomLineFactor factor(SplineTiming::of(spline), 0.0, E(0), D(0), L(0),
                                   {t_recorded, sighting.u + 3.0}, uhiCamera(), lineNoise());
  const auto cost = factor.createCostFunction();
  const double epsilon = 1e-9;
  const auto before = evaluate(*cost, stateOf(spline, factor, extrinsic(), -epsilon, &sighting.p_W));
  const auto after = evaluate(*cost, stateOf(spline, factor, extrinsic(), epsilon, &sighting.p_W));
  EXPECT_NEAR(before.residual[0], after.residual[0], 1e-5);
  EXPECT_NEAR(before.residual[1], after.residual[1], 1e-9);
  // The spline is C2, so the time derivative is continuous there too.
  const double du_dd = before.jacobians[6](0, 0);
  EXPECT_NEAR(after.jacobians[6](0, 0), du_dd, 1e-6 * std::max(1.0, std::abs(du_dd)));
}

TEST(PushbroomLineFactor, RejectsBadSplinesTimesAndNoise) {
  try {
    PushbroomLineFactor(SplineTiming{kT0, kDt, 4}, 0.0, E(0), D(0), L(0), {kT0 + 0.5 * kDt, 10.0},
                        uhiCamera(), lineNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "PushbroomLineFactor: the spline needs at least 5 control points (the factor "
                 "spans two segments), got 4");
  }
  EXPECT_THROW(PushbroomLineFactor(SplineTiming{kT0, kDt, kNumControlPoints}, -0.5, E(0), D(0),
                                   L(0), {kT0 + 0.1, 10.0}, uhiCamera(), lineNoise()),
               std::out_of_range);
  try {
    PushbroomLineFactor(SplineTiming{kT0, kDt, kNumControlPoints}, 0.0, E(0), D(0), L(0),
                        {kT0 + 0.5, 10.0}, uhiCamera(), NoiseModel::isotropic(3, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "PushbroomLineFactor: the noise model has dimension 3, expected 2 (one per "
                 "residual component)");
  }
  try {
    PushbroomLineFactor(SplineTiming{kT0, kDt, kNumControlPoints}, 0.0, E(0), D(0),
                        Eigen::Vector3d(0.0, std::nan(""), 0.0), {kT0 + 0.5, 10.0}, uhiCamera(),
                        lineNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "PushbroomLineFactor: fixed point p_W must be finite, got nan");
  }
}

}  // namespace
}  // namespace hsmap
