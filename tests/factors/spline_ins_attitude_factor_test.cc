#include "factors/spline_ins_attitude_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "factors/ins_attitude_factor.h"
#include "tests/factors/factor_test_support.h"
#include "tests/factors/spline_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

constexpr double kT0 = 5.0;
constexpr double kDt = 0.1;

NoiseModel attitudeNoise() {
  return NoiseModel::fromSigmas(Eigen::Vector3d(0.05, 0.05, 0.2) * std::numbers::pi / 180.0);
}

SE3d bodyToCamera() {
  return SE3d(expSO3(Eigen::Vector3d(0.1, -0.2, 1.4)), Eigen::Vector3d(0.5, -0.1, 0.3));
}

SE3Splined wobblyTrajectory(std::mt19937& rng, int num_control_points) {
  return test::wobblyTrajectory(rng, kT0, kDt, num_control_points);
}

std::vector<test::ParameterBlock> stateOf(const SE3Splined& spline, const SplineSegment& segment) {
  return test::segmentState(spline, segment);
}

TEST(SplineInsAttitudeFactor, ConnectsTheFourActiveControlPoints) {
  const SplineTiming timing{kT0, kDt, 10};
  const Eigen::Quaterniond q(expSO3(Eigen::Vector3d(0.1, 0.2, 0.3)));
  const SplineInsAttitudeFactor factor(timing, kT0 + 6.5 * kDt, q, bodyToCamera(),
                                       attitudeNoise());
  EXPECT_EQ(factor.name(), "SplineInsAttitudeFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(6), S(7), S(8), S(9)}));
  EXPECT_EQ(factor.residualDimension(), 3);
  EXPECT_DOUBLE_EQ(factor.fixTime(), kT0 + 6.5 * kDt);
  EXPECT_EQ(factor.segment().first_control_point, 6);
  EXPECT_NEAR(factor.segment().u, 0.5, 1e-12);
  EXPECT_LT(factor.measuredAttitude().angularDistance(q), 1e-12);
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7, 7}));
}

TEST(SplineInsAttitudeFactor, ResidualMatchesHandComputedOnAConstantRotationSpline) {
  // All control points yawed 90 degrees, so q_W_C(t) = Rz(90) at any t.
  // q_B_C = Rx(0.3), measured q_W_B = Rz(90) Rx(-0.2):
  // r = log(Rx(0.2) Rz(-90) Rz(90) Rx(-0.3)) = log(Rx(-0.1)) = (-0.1, 0, 0).
  const Eigen::Quaterniond yaw90 = expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0));
  const SplineTiming timing{kT0, kDt, 6};
  const SplineInsAttitudeFactor factor(
      timing, kT0 + 1.7 * kDt, yaw90 * expSO3(Eigen::Vector3d(-0.2, 0.0, 0.0)),
      SE3d(expSO3(Eigen::Vector3d(0.3, 0.0, 0.0)), Eigen::Vector3d(0.5, 0.0, 0.3)),
      attitudeNoise());
  std::vector<test::ParameterBlock> blocks;
  for (int j = 1; j <= 4; ++j) blocks.push_back(poseBlock(SE3d(yaw90, Eigen::Vector3d(0.5 * j, 0, 0))));
  const auto evaluation = evaluate(*factor.createCostFunction(), blocks);
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], -0.1, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], 0.0, 1e-12);
  EXPECT_NEAR(evaluation.residual[2], 0.0, 1e-12);
}

TEST(SplineInsAttitudeFactor, ResidualIsZeroAtTheTruthAndMinusTheAttitudeErrorOffIt) {
  std::mt19937 rng(83);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  const SE3d T_B_C = bodyToCamera();
  for (int trial = 0; trial < 10; ++trial) {
    const double t_fix =
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng);
    const Eigen::Quaterniond q_W_B = (spline.pose(t_fix) * T_B_C.inverse()).q;
    const SplineInsAttitudeFactor truth(SplineTiming::of(spline), t_fix, q_W_B, T_B_C,
                                        attitudeNoise());
    const auto blocks = stateOf(spline, truth.segment());
    EXPECT_LT(evaluate(*truth.createCostFunction(), blocks).residual.norm(), 1e-12)
        << "trial " << trial;

    // Measured q_W_B exp(d) gives r = log(exp(-d)) = -d, the keyframe factor's residual.
    const Eigen::Vector3d d(0.01 * trial, -0.02, 0.03);
    const Eigen::Quaterniond measured = q_W_B * expSO3(d);
    const SplineInsAttitudeFactor off(SplineTiming::of(spline), t_fix, measured, T_B_C,
                                      attitudeNoise());
    const Eigen::VectorXd r = evaluate(*off.createCostFunction(), blocks).residual;
    EXPECT_LT((r + d).norm(), 1e-12) << "trial " << trial;
    const InsAttitudeFactor keyframe(X(0), measured, T_B_C, attitudeNoise());
    EXPECT_LT((r - evaluate(*keyframe.createCostFunction(), {poseBlock(spline.pose(t_fix))}).residual)
                  .norm(),
              1e-12)
        << "trial " << trial;
  }
}

TEST(SplineInsAttitudeFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(84);
  const SE3Splined spline = wobblyTrajectory(rng, 12);
  std::vector<double> times = {spline.validBegin(), kT0 + 4.0 * kDt, spline.validEnd()};
  for (int trial = 0; trial < 8; ++trial) {
    times.push_back(
        std::uniform_real_distribution<double>(spline.validBegin(), spline.validEnd())(rng));
  }
  for (const double t_fix : times) {
    const Eigen::Quaterniond measured = (spline.pose(t_fix) * bodyToCamera().inverse()).q *
                                        expSO3(Eigen::Vector3d(0.05, -0.1, 0.2));
    const SplineInsAttitudeFactor factor(SplineTiming::of(spline), t_fix, measured,
                                         bodyToCamera(), attitudeNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             stateOf(spline, factor.segment())))
        << "t_fix " << t_fix;
  }
}

TEST(SplineInsAttitudeFactor, RejectsAFixOutsideTheSplineAndBadArguments) {
  const SplineTiming timing{kT0, kDt, 6};
  const Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  EXPECT_THROW(SplineInsAttitudeFactor(timing, kT0 - 1e-3, q, bodyToCamera(), attitudeNoise()),
               std::out_of_range);
  EXPECT_THROW(
      SplineInsAttitudeFactor(timing, kT0 + 3.0 * kDt + 1e-3, q, bodyToCamera(), attitudeNoise()),
      std::out_of_range);
  try {
    SplineInsAttitudeFactor(timing, kT0, q, bodyToCamera(), NoiseModel::isotropic(6, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineInsAttitudeFactor: the noise model has dimension 6, expected 3 (one per "
                 "residual component)");
  }
  try {
    SplineInsAttitudeFactor(timing, kT0, Eigen::Quaterniond(0.5, 0.0, 0.0, 0.0), bodyToCamera(),
                            attitudeNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineInsAttitudeFactor: measured attitude q_W_B must be a unit quaternion, got "
                 "norm 0.5");
  }
  EXPECT_THROW(SplineInsAttitudeFactor(
                   timing, kT0, q,
                   SE3d(Eigen::Quaterniond(1.0, 1.0, 0.0, 0.0), Eigen::Vector3d::Zero()),
                   attitudeNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
