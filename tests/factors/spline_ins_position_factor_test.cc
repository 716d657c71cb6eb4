#include "factors/spline_ins_position_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "factors/ins_position_factor.h"
#include "tests/factors/factor_test_support.h"
#include "tests/factors/spline_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

constexpr double kT0 = 5.0;
constexpr double kDt = 0.1;

NoiseModel insNoise() { return NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 0.5, 0.05)); }

// Lever arm and mounting rotation, neither trivial.
SE3d bodyToCamera() {
  return SE3d(expSO3(Eigen::Vector3d(0.1, -0.2, 1.4)), Eigen::Vector3d(0.5, -0.1, 0.3));
}

SE3Splined wobblyTrajectory(std::mt19937& rng, int num_control_points) {
  return test::wobblyTrajectory(rng, kT0, kDt, num_control_points);
}

std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline, const SplineSegment& segment) {
  return test::segmentState(spline, segment);
}

TEST(SplineInsPositionFactor, ConnectsTheFourActiveControlPoints) {
  const SplineTiming timing{kT0, kDt, 10};
  const SplineInsPositionFactor factor(timing, kT0 + 3.25 * kDt, Eigen::Vector3d(1.0, 2.0, 3.0),
                                       bodyToCamera(), insNoise(), RobustLoss::huber(1.0));
  EXPECT_EQ(factor.name(), "SplineInsPositionFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(3), S(4), S(5), S(6)}));
  EXPECT_EQ(factor.residualDimension(), 3);
  EXPECT_DOUBLE_EQ(factor.fixTime(), kT0 + 3.25 * kDt);
  EXPECT_EQ(factor.segment().first_control_point, 3);
  EXPECT_NEAR(factor.segment().u, 0.25, 1e-12);
  EXPECT_EQ(factor.measuredPosition(), Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7, 7}));
}

TEST(SplineInsPositionFactor, ResidualMatchesHandComputedLeverArmOnAStraightLineSpline) {
  // Control points S(j) = (Rz(90), (0.5 j, 0, 0)): the cumulative basis sums
  // to 1 + u, so at segment i, time u the camera is at x = 0.5 (i + 1 + u),
  // yawed 90 degrees. t = t0 + 1.25 dt: i = 1, u = 0.25, t_W_C = (1.125, 0, 0).
  // T_B_C = (I, (0.5, 0, 0.3)): t_C_B = (-0.5, 0, -0.3), R t_C_B = (0, -0.5, -0.3),
  // t_W_B = (1.125, -0.5, -0.3); against the fix (1, -0.4, -0.3): r = (0.125, -0.1, 0).
  const Eigen::Quaterniond yaw90 = expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0));
  const SplineTiming timing{kT0, kDt, 6};
  const SplineInsPositionFactor factor(
      timing, kT0 + 1.25 * kDt, Eigen::Vector3d(1.0, -0.4, -0.3),
      SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, 0.0, 0.3)), insNoise());
  std::vector<test::ParameterBlock> blocks;
  for (int j = 1; j <= 4; ++j) blocks.push_back(poseBlock(SE3d(yaw90, Eigen::Vector3d(0.5 * j, 0, 0))));
  const auto evaluation = evaluate(*factor.createCostFunction(), blocks);
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 0.125, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], -0.1, 1e-12);
  EXPECT_NEAR(evaluation.residual[2], 0.0, 1e-12);
}

TEST(SplineInsPositionFactor, ResidualIsZeroAtTheTruthAndMinusTheFixErrorOffIt) {
  std::mt19937 rng(81);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const SE3d T_B_C = bodyToCamera();
  for (int trial = 0; trial < 10; ++trial) {
    const double t_fix =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const SE3d T_W_B = spline.pose(t_fix) * T_B_C.inverse();
    const SplineInsPositionFactor truth(SplineTiming::of(spline), t_fix, T_W_B.t, T_B_C,
                                        insNoise());
    const auto blocks = stateOf(spline, truth.segment());
    EXPECT_LT(evaluate(*truth.createCostFunction(), blocks).residual.norm(), 1e-12 * 100.0)
        << "trial " << trial;

    // A fix off by d gives r = -d, the residual of the keyframe factor at T_W_C(t_fix).
    const Eigen::Vector3d d(0.03 * trial, -0.02, 0.01 + 0.005 * trial);
    const SplineInsPositionFactor off(SplineTiming::of(spline), t_fix, T_W_B.t + d, T_B_C,
                                      insNoise());
    const Eigen::VectorXd r = evaluate(*off.createCostFunction(), blocks).residual;
    EXPECT_LT((r + d).norm(), 1e-12 * 100.0) << "trial " << trial;
    const InsPositionFactor keyframe(X(0), T_W_B.t + d, T_B_C, insNoise());
    EXPECT_LT((r - evaluate(*keyframe.createCostFunction(), {poseBlock(spline.pose(t_fix))}).residual)
                  .norm(),
              1e-12 * 100.0)
        << "trial " << trial;
  }
}

TEST(SplineInsPositionFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(82);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  std::vector<double> times = {spline.validBegin(), kT0 + 4.0 * kDt, spline.validEnd()};
  for (int trial = 0; trial < 8; ++trial) {
    times.push_back(
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng));
  }
  for (const double t_fix : times) {
    const SplineInsPositionFactor factor(
        SplineTiming::of(spline), t_fix,
        (spline.pose(t_fix) * bodyToCamera().inverse()).t + Eigen::Vector3d(0.3, -0.2, 0.1),
        bodyToCamera(), insNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             stateOf(spline, factor.segment())))
        << "t_fix " << t_fix;
  }
}

TEST(SplineInsPositionFactor, RejectsAFixOutsideTheSplineAndBadArguments) {
  const SplineTiming timing{kT0, kDt, 6};
  const Eigen::Vector3d fix(1.0, 2.0, 3.0);
  EXPECT_THROW(SplineInsPositionFactor(timing, kT0 - 0.01, fix, bodyToCamera(), insNoise()),
               std::out_of_range);
  EXPECT_THROW(
      SplineInsPositionFactor(timing, kT0 + 3.0 * kDt + 0.01, fix, bodyToCamera(), insNoise()),
      std::out_of_range);
  try {
    SplineInsPositionFactor(timing, kT0, fix, bodyToCamera(), NoiseModel::isotropic(2, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineInsPositionFactor: the noise model has dimension 2, expected 3 (one per "
                 "residual component)");
  }
  try {
    SplineInsPositionFactor(timing, kT0, fix,
                            SE3d(Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0), Eigen::Vector3d::Zero()),
                            insNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineInsPositionFactor: T_B_C rotation must be a unit quaternion, got norm 2");
  }
  EXPECT_THROW(SplineInsPositionFactor(timing, kT0, Eigen::Vector3d(0.0, std::nan(""), 0.0),
                                       bodyToCamera(), insNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
