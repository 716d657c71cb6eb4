#include "factors/ins_attitude_factor.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

constexpr double kPi = std::numbers::pi;

NoiseModel attitudeNoise() {
  return NoiseModel::fromSigmas(Eigen::Vector3d(0.05, 0.05, 0.2) * (kPi / 180.0));
}

Eigen::Quaterniond rotation(double x, double y, double z) {
  return expSO3(Eigen::Vector3d(x, y, z));
}

TEST(InsAttitudeFactor, NamesItsMeasurementAndKey) {
  const InsAttitudeFactor factor(X(9), Eigen::Quaterniond::Identity(), SE3d(), attitudeNoise());
  EXPECT_EQ(factor.name(), "InsAttitudeFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{X(9)}));
  EXPECT_EQ(factor.residualDimension(), 3);
}

TEST(InsAttitudeFactor, ResidualIsTheErrorRotationInTheBodyFrame) {
  // Measured q_W_B = Rz(90deg); the camera's rotation implies
  // q_W_B = Rz(90deg) * Rx(0.1), i.e. an extra roll of 0.1 rad about the
  // body's x axis (in W that axis is y: a residual in W would read (0, 0.1, 0)).
  // The camera is mounted with q_B_C = Ry(90deg), so q_W_C = q_W_B * q_B_C.
  const Eigen::Quaterniond q_B_C = rotation(0.0, kPi / 2.0, 0.0);
  const Eigen::Quaterniond q_W_B_true = rotation(0.0, 0.0, kPi / 2.0) * rotation(0.1, 0.0, 0.0);
  const SE3d T_W_C(q_W_B_true * q_B_C, Eigen::Vector3d(5.0, -2.0, 30.0));
  const InsAttitudeFactor factor(X(0), rotation(0.0, 0.0, kPi / 2.0),
                                 SE3d(q_B_C, Eigen::Vector3d(0.5, 0.0, 0.3)), attitudeNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(T_W_C)});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 0.1, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], 0.0, 1e-12);
  EXPECT_NEAR(evaluation.residual[2], 0.0, 1e-12);
}

TEST(InsAttitudeFactor, ResidualIsZeroForTheAttitudeOfTheTruePose) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector3d roll_pitch_heading =
        test::randomVector(rng, Eigen::Vector3d(-30, -30, -180), Eigen::Vector3d(30, 30, 180));
    const Eigen::Quaterniond q_W_B = quaternionFromRollPitchHeadingDeg(
        roll_pitch_heading[0], roll_pitch_heading[1], roll_pitch_heading[2]);
    const SE3d T_B_C = test::randomPose(rng, 2.0, 1.0);
    const SE3d T_W_C = SE3d(q_W_B, Eigen::Vector3d(1.0, 2.0, 3.0)) * T_B_C;
    const InsAttitudeFactor factor(X(0), q_W_B, T_B_C, attitudeNoise());
    const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(T_W_C)});
    EXPECT_LT(evaluation.residual.norm(), 1e-12) << "trial " << trial;
  }
}

TEST(InsAttitudeFactor, JacobianMatchesNumericTangentDifferences) {
  std::mt19937 rng(32);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_C = test::randomPose(rng, 3.0, 20.0);
    const SE3d T_B_C = test::randomPose(rng, 2.0, 1.0);
    // A measurement off by a sizeable rotation (up to ~1 rad).
    const Eigen::Quaterniond q_W_B = (T_W_C * T_B_C.inverse()).q * test::randomPose(rng, 1.0, 0.0).q;
    const InsAttitudeFactor factor(X(0), q_W_B, T_B_C, attitudeNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {poseBlock(T_W_C)}))
        << "trial " << trial;
  }
}

TEST(InsAttitudeFactor, RejectsBadArguments) {
  try {
    InsAttitudeFactor(X(0), Eigen::Quaterniond(0.5, 0.0, 0.0, 0.0), SE3d(), attitudeNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "InsAttitudeFactor: measured attitude q_W_B must be a unit quaternion, got norm "
                 "0.5");
  }
  try {
    InsAttitudeFactor(X(0), Eigen::Quaterniond::Identity(), SE3d(), NoiseModel::isotropic(6, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "InsAttitudeFactor: the noise model has dimension 6, expected 3 (one per "
                 "residual component)");
  }
}

}  // namespace
}  // namespace hsmap
