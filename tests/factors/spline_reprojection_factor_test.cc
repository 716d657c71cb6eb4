#include "factors/spline_reprojection_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "factors/reprojection_factor.h"
#include "tests/factors/factor_test_support.h"
#include "tests/factors/reference_jacobians.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;
using test::vectorBlock;

constexpr double kT0 = 2.0;
constexpr double kDt = 0.1;

PinholeRadtanParameters camera() { return test::pinholeTestCamera(); }

PinholeRadtanParameters distortedCamera() {
  PinholeRadtanParameters p = camera();
  p.distortion = {-0.12, 0.05, 0.001, -0.0005, 0.01};
  return p;
}

NoiseModel pixelNoise() { return NoiseModel::isotropic(2, 1.0); }

// A survey-like trajectory: forward motion with a slow turn and some roll and
// pitch wobble, plus per-control-point perturbations so no segment is special.
SE3Splined wobblyTrajectory(std::mt19937& rng, int num_control_points) {
  std::vector<SE3d> control_points;
  for (int k = 0; k < num_control_points; ++k) {
    const double t = kT0 + (k - 1) * kDt;
    const SE3d nominal(expSO3(Eigen::Vector3d(0.2 * std::sin(3.0 * t), 0.1 * std::cos(2.0 * t),
                                              0.3 * t)),
                       Eigen::Vector3d(1.5 * t, 0.4 * std::sin(t), 10.0 + 0.2 * t));
    control_points.push_back(nominal * test::randomPose(rng, 0.05, 0.03));
  }
  return SE3Splined(kT0, kDt, control_points);
}

std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline, const SplineSegment& segment,
                                          const Eigen::Vector3d& p_W) {
  std::vector<test::ParameterBlock> blocks;
  for (int k = 0; k < 4; ++k) {
    blocks.push_back(poseBlock(spline.controlPoints()[segment.first_control_point + k]));
  }
  blocks.push_back(vectorBlock(p_W));
  return blocks;
}

TEST(SplineReprojectionFactor, ConnectsTheFourActiveControlPointsThenTheLandmark) {
  const SplineTiming timing{kT0, kDt, 10};
  const SplineReprojectionFactor factor(timing, kT0 + 3.25 * kDt, L(7),
                                        Eigen::Vector2d(10.0, 20.0), camera(), pixelNoise(),
                                        RobustLoss::cauchy(2.0));
  EXPECT_EQ(factor.name(), "SplineReprojectionFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(3), S(4), S(5), S(6), L(7)}));
  EXPECT_EQ(factor.segment().first_control_point, 3);
  EXPECT_NEAR(factor.segment().u, 0.25, 1e-12);
  EXPECT_EQ(factor.robustLoss().toString(), "cauchy(2)");
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7, 7, 3}));
}

TEST(SplineReprojectionFactor, ResidualMatchesHandComputedPixelOnAStraightLineSpline) {
  // Control points S(j) = (I, (0.5 j, 0, 0)): the cumulative basis sums to
  // 1 + u, so at segment i, time u the camera is at x = 0.5 (i + 1 + u).
  // t = t0 + 1.25 dt: i = 1, u = 0.25, x = 1.125. The landmark
  // (1.225, -0.2, 2) is at p_C = (0.1, -0.2, 2): pixel (520, 200).
  const SplineTiming timing{kT0, kDt, 6};
  const SplineReprojectionFactor factor(timing, kT0 + 1.25 * kDt, L(0),
                                        Eigen::Vector2d(515.0, 203.0), camera(), pixelNoise());
  std::vector<test::ParameterBlock> blocks;
  for (int j = 1; j <= 4; ++j) {
    blocks.push_back(poseBlock(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5 * j, 0, 0))));
  }
  blocks.push_back(vectorBlock(Eigen::Vector3d(1.225, -0.2, 2.0)));
  const auto evaluation = evaluate(*factor.createCostFunction(), blocks);
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 5.0, 1e-9);
  EXPECT_NEAR(evaluation.residual[1], -3.0, 1e-9);
}

TEST(SplineReprojectionFactor, ResidualIsZeroAtTheTrueStateAndMatchesTheKeyframeFactor) {
  std::mt19937 rng(71);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const PinholeRadtanCamera pinhole(distortedCamera());
  for (int trial = 0; trial < 10; ++trial) {
    const double t_frame =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const SE3d T_W_C = spline.pose(t_frame);
    const Eigen::Vector3d p_C =
        test::randomVector(rng, Eigen::Vector3d(-1.0, -0.7, 2.0), Eigen::Vector3d(1.0, 0.7, 8.0));
    const Eigen::Vector3d p_W = T_W_C * p_C;
    const SplineReprojectionFactor factor(SplineTiming::of(spline), t_frame, L(0),
                                          pinhole.project(p_C), distortedCamera(), pixelNoise());
    const auto blocks = stateOf(spline, factor.segment(), p_W);
    EXPECT_LT(evaluate(*factor.createCostFunction(), blocks).residual.norm(), 1e-8);

    // Off the true pixel, the residual is that of a keyframe factor at T_W_C(t).
    const Eigen::Vector2d pixel(100.0 + 50.0 * trial, 400.0 - 20.0 * trial);
    const SplineReprojectionFactor off(SplineTiming::of(spline), t_frame, L(0), pixel,
                                       distortedCamera(), pixelNoise());
    const ReprojectionFactor keyframe(X(0), L(0), pixel, distortedCamera(), pixelNoise());
    const Eigen::VectorXd expected =
        evaluate(*keyframe.createCostFunction(), {poseBlock(T_W_C), vectorBlock(p_W)}).residual;
    EXPECT_LT((evaluate(*off.createCostFunction(), blocks).residual - expected).norm(), 1e-8)
        << "trial " << trial;
  }
}

TEST(SplineReprojectionFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(72);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  for (int trial = 0; trial < 10; ++trial) {
    const double t_frame =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const Eigen::Vector3d p_W =
        spline.pose(t_frame) *
        test::randomVector(rng, Eigen::Vector3d(-1.0, -0.7, 2.0), Eigen::Vector3d(1.0, 0.7, 8.0));
    const SplineReprojectionFactor factor(SplineTiming::of(spline), t_frame, L(0),
                                          Eigen::Vector2d(300.0, 200.0), distortedCamera(),
                                          pixelNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             stateOf(spline, factor.segment(), p_W)))
        << "trial " << trial;
  }
}

TEST(SplineReprojectionFactor, AnalyticJacobiansEqualTheAutodiffOnesInTheTangentSpace) {
  std::mt19937 rng(73);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  // Random frame times plus the ends of segments (u = 0 and u -> 1).
  std::vector<double> frame_times = {kT0 + 4.0 * kDt, kT0 + 5.0 * kDt - 1e-9, spline.validEnd()};
  for (int trial = 0; trial < 20; ++trial) {
    frame_times.push_back(
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng));
  }
  for (const double t_frame : frame_times) {
    const Eigen::Vector3d p_W =
        spline.pose(t_frame) *
        test::randomVector(rng, Eigen::Vector3d(-1.5, -0.9, 1.0), Eigen::Vector3d(1.5, 0.9, 9.0));
    const SplineReprojectionFactor factor(SplineTiming::of(spline), t_frame, L(0),
                                          Eigen::Vector2d(310.0, 190.0), distortedCamera(),
                                          pixelNoise());
    EXPECT_TRUE(test::tangentJacobiansMatchReference(*factor.createCostFunction(),
                                                     *factor.createAutoDiffCostFunction(),
                                                     stateOf(spline, factor.segment(), p_W)))
        << "t_frame " << t_frame;
  }
}

TEST(SplineReprojectionFactor, AnalyticJacobiansHoldBehindTheCameraWhereTheDepthIsFloored) {
  std::mt19937 rng(74);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const double t_frame = kT0 + 4.6 * kDt;
  const SplineReprojectionFactor factor(SplineTiming::of(spline), t_frame, L(0),
                                        Eigen::Vector2d(310.0, 190.0), distortedCamera(),
                                        pixelNoise());
  // Depths below the 1 cm floor: just below it, at zero and behind the camera.
  for (const double z_C : {0.009, 0.0, -0.5}) {
    const Eigen::Vector3d p_W = spline.pose(t_frame) * Eigen::Vector3d(0.002, -0.001, z_C);
    const auto blocks = stateOf(spline, factor.segment(), p_W);
    EXPECT_TRUE(test::tangentJacobiansMatchReference(*factor.createCostFunction(),
                                                     *factor.createAutoDiffCostFunction(), blocks))
        << "z_C " << z_C;
    // Far behind the camera the residual (~1e9) curves too sharply for the
    // h = 1e-4 difference quotient; near the floor it is still a fair reference.
    if (z_C >= 0.0) {
      EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), blocks))
          << "z_C " << z_C;
    }
  }
}

TEST(SplineReprojectionFactor, JacobiansOfSomeBlocksOnlyEqualThoseOfAFullEvaluation) {
  // Ceres passes null for the Jacobians of constant blocks.
  std::mt19937 rng(75);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const double t_frame = kT0 + 6.3 * kDt;
  const SplineReprojectionFactor factor(SplineTiming::of(spline), t_frame, L(0),
                                        Eigen::Vector2d(500.0, 250.0), distortedCamera(),
                                        pixelNoise());
  const auto blocks =
      stateOf(spline, factor.segment(), spline.pose(t_frame) * Eigen::Vector3d(0.2, 0.1, 4.0));
  const auto cost = factor.createCostFunction();
  EXPECT_TRUE(test::partialJacobiansMatchFull(*cost, blocks, {false, true, false, true, false}));
  EXPECT_TRUE(test::partialJacobiansMatchFull(*cost, blocks, {true, false, true, false, true}));
  EXPECT_TRUE(test::partialJacobiansMatchFull(*cost, blocks, {false, false, false, false, true}));
}

TEST(SplineReprojectionFactor, ASharedCameraGivesWhatACameraOfItsOwnGives) {
  std::mt19937 rng(74);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const auto shared = std::make_shared<const PinholeRadtanCamera>(distortedCamera());
  for (int trial = 0; trial < 5; ++trial) {
    const double t_frame =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const Eigen::Vector3d p_W =
        spline.pose(t_frame) *
        test::randomVector(rng, Eigen::Vector3d(-1.0, -0.7, 2.0), Eigen::Vector3d(1.0, 0.7, 8.0));
    const Eigen::Vector2d pixel(300.0 + 10.0 * trial, 200.0);
    const SplineReprojectionFactor own(SplineTiming::of(spline), t_frame, L(0), pixel,
                                       distortedCamera(), pixelNoise());
    const SplineReprojectionFactor with_shared(SplineTiming::of(spline), t_frame, L(0), pixel,
                                               shared, pixelNoise());
    const auto blocks = stateOf(spline, own.segment(), p_W);
    const test::Evaluation a = evaluate(*own.createCostFunction(), blocks);
    const test::Evaluation b = evaluate(*with_shared.createCostFunction(), blocks);
    ASSERT_TRUE(a.ok && b.ok);
    EXPECT_EQ(a.residual, b.residual) << "trial " << trial;
    ASSERT_EQ(a.jacobians.size(), b.jacobians.size());
    for (std::size_t k = 0; k < a.jacobians.size(); ++k) EXPECT_EQ(a.jacobians[k], b.jacobians[k]);
    EXPECT_GT(a.residual.norm(), 1.0);  // a pixel off the projection: not a trivial zero
  }
  // The factors and their cost functions hold the one camera, not copies.
  const SplineReprojectionFactor factor(SplineTiming::of(spline), kT0 + 2.5 * kDt, L(0),
                                        Eigen::Vector2d(1.0, 2.0), shared, pixelNoise());
  const auto cost = factor.createCostFunction();
  EXPECT_EQ(shared.use_count(), 3);
  EXPECT_THROW(SplineReprojectionFactor(SplineTiming::of(spline), kT0 + 2.5 * kDt, L(0),
                                        Eigen::Vector2d(1.0, 2.0),
                                        std::shared_ptr<const PinholeRadtanCamera>(), pixelNoise()),
               std::invalid_argument);
}

TEST(SplineReprojectionFactor, RejectsAFrameOutsideTheSplineAndAWrongNoise) {
  const SplineTiming timing{kT0, kDt, 6};
  EXPECT_THROW(SplineReprojectionFactor(timing, kT0 - 0.01, L(0), Eigen::Vector2d(1.0, 2.0),
                                        camera(), pixelNoise()),
               std::out_of_range);
  EXPECT_THROW(SplineReprojectionFactor(timing, kT0 + 3.0 * kDt + 0.01, L(0),
                                        Eigen::Vector2d(1.0, 2.0), camera(), pixelNoise()),
               std::out_of_range);
  try {
    SplineReprojectionFactor(timing, kT0, L(0), Eigen::Vector2d(1.0, 2.0), camera(),
                             NoiseModel::isotropic(3, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineReprojectionFactor: the noise model has dimension 3, expected 2 (one per "
                 "residual component)");
  }
}

}  // namespace
}  // namespace hsmap
