#include "factors/spline_pose_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "factors/pose_prior_factor.h"
#include "tests/factors/factor_test_support.h"
#include "tests/factors/spline_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

constexpr double kT0 = 5.0;
constexpr double kDt = 0.1;

NoiseModel poseNoise() {
  return NoiseModel::fromSigmas((Vector6d() << 0.02, 0.02, 0.02, 0.01, 0.01, 0.01).finished());
}

SE3Splined wobblyTrajectory(std::mt19937& rng, int num_control_points) {
  return test::wobblyTrajectory(rng, kT0, kDt, num_control_points);
}

std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline, const SplineSegment& segment) {
  return test::segmentState(spline, segment);
}

TEST(SplinePoseFactor, ConnectsTheFourActiveControlPoints) {
  const SplineTiming timing{kT0, kDt, 10};
  const SE3d measured(expSO3(Eigen::Vector3d(0.1, 0.2, 0.3)), Eigen::Vector3d(1.0, 2.0, 3.0));
  // The end of the valid range belongs to the last segment, u = 1.
  const SplinePoseFactor factor(timing, kT0 + 7.0 * kDt, measured, poseNoise());
  EXPECT_EQ(factor.name(), "SplinePoseFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(6), S(7), S(8), S(9)}));
  EXPECT_EQ(factor.residualDimension(), 6);
  EXPECT_DOUBLE_EQ(factor.time(), kT0 + 7.0 * kDt);
  EXPECT_EQ(factor.segment().first_control_point, 6);
  EXPECT_NEAR(factor.segment().u, 1.0, 1e-12);
  EXPECT_EQ(factor.measuredPose().t, measured.t);
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7, 7}));
}

TEST(SplinePoseFactor, ResidualMatchesHandComputedOnAStraightLineSpline) {
  // Control points S(j) = (Rz(90), (0.5 j, 0, 0)): at t = t0 + 1.25 dt
  // (i = 1, u = 0.25) T_W_C = (Rz(90), (1.125, 0, 0)). Against the measured
  // (Rz(90), (1, 0, 0)): T_measured^-1 T_W_C = (I, Rz(-90) (0.125, 0, 0))
  // = (I, (0, -0.125, 0)), whose log is [rho; phi] = [0, -0.125, 0; 0, 0, 0].
  const Eigen::Quaterniond yaw90 = expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0));
  const SplineTiming timing{kT0, kDt, 6};
  const SplinePoseFactor factor(timing, kT0 + 1.25 * kDt,
                                SE3d(yaw90, Eigen::Vector3d(1.0, 0.0, 0.0)), poseNoise());
  std::vector<test::ParameterBlock> blocks;
  for (int j = 1; j <= 4; ++j) blocks.push_back(poseBlock(SE3d(yaw90, Eigen::Vector3d(0.5 * j, 0, 0))));
  const auto evaluation = evaluate(*factor.createCostFunction(), blocks);
  ASSERT_TRUE(evaluation.ok);
  Vector6d expected;
  expected << 0.0, -0.125, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT((evaluation.residual - expected).norm(), 1e-12) << evaluation.residual.transpose();
}

TEST(SplinePoseFactor, ResidualIsZeroAtTheTruthAndTheTangentErrorOffIt) {
  std::mt19937 rng(85);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  for (int trial = 0; trial < 10; ++trial) {
    const double t =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const SE3d T_W_C = spline.pose(t);
    const SplinePoseFactor truth(SplineTiming::of(spline), t, T_W_C, poseNoise());
    const auto blocks = stateOf(spline, truth.segment());
    EXPECT_LT(evaluate(*truth.createCostFunction(), blocks).residual.norm(), 1e-12)
        << "trial " << trial;

    // Measured T_W_C exp(-d) gives r = log(exp(d)) = d, PosePriorFactor's residual at T_W_C(t).
    Vector6d d;
    d << 0.05, -0.02 * trial, 0.01, 0.02, -0.03, 0.004 * trial;
    const SE3d measured = T_W_C * SE3d::exp(Vector6d(-d));
    const SplinePoseFactor off(SplineTiming::of(spline), t, measured, poseNoise());
    const Eigen::VectorXd r = evaluate(*off.createCostFunction(), blocks).residual;
    EXPECT_LT((r - d).norm(), 1e-10) << "trial " << trial;
    const PosePriorFactor keyframe(X(0), measured, poseNoise());
    EXPECT_LT((r - evaluate(*keyframe.createCostFunction(), {poseBlock(T_W_C)}).residual).norm(),
              1e-10)
        << "trial " << trial;
  }
}

TEST(SplinePoseFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(86);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  std::vector<double> times = {spline.validBegin(), kT0 + 4.0 * kDt, spline.validEnd()};
  for (int trial = 0; trial < 8; ++trial) {
    times.push_back(
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng));
  }
  for (const double t : times) {
    const SE3d measured = spline.pose(t) * test::randomPose(rng, 0.2, 0.3);
    const SplinePoseFactor factor(SplineTiming::of(spline), t, measured, poseNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             stateOf(spline, factor.segment())))
        << "t " << t;
  }
}

TEST(SplinePoseFactor, RejectsATimeOutsideTheSplineAndBadArguments) {
  const SplineTiming timing{kT0, kDt, 6};
  const SE3d measured;
  EXPECT_THROW(SplinePoseFactor(timing, kT0 - 1e-3, measured, poseNoise()), std::out_of_range);
  EXPECT_THROW(SplinePoseFactor(timing, kT0 + 3.0 * kDt + 1e-3, measured, poseNoise()),
               std::out_of_range);
  EXPECT_THROW(SplinePoseFactor(timing, std::nan(""), measured, poseNoise()), std::out_of_range);
  try {
    SplinePoseFactor(timing, kT0, measured, NoiseModel::isotropic(3, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplinePoseFactor: the noise model has dimension 3, expected 6 (one per "
                 "residual component)");
  }
  try {
    SplinePoseFactor(timing, kT0, SE3d(Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0), Eigen::Vector3d::Zero()),
                     poseNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplinePoseFactor: measured pose T_W_C rotation must be a unit quaternion, got "
                 "norm 2");
  }
  EXPECT_THROW(SplinePoseFactor(timing, kT0,
                                SE3d(Eigen::Quaterniond::Identity(),
                                     Eigen::Vector3d(0.0, 0.0, std::nan(""))),
                                poseNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
