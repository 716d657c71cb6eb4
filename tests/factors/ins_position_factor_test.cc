#include "factors/ins_position_factor.h"

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

NoiseModel insNoise() { return NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 0.5, 0.05)); }

SE3d leverArm() { return SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, 0.0, 0.3)); }

TEST(InsPositionFactor, NamesItsMeasurementAndKey) {
  const InsPositionFactor factor(X(4), Eigen::Vector3d(1.0, 2.0, 3.0), leverArm(), insNoise());
  EXPECT_EQ(factor.name(), "InsPositionFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{X(4)}));
  EXPECT_EQ(factor.residualDimension(), 3);
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(), (std::vector<int32_t>{7}));
}

TEST(InsPositionFactor, ResidualMatchesHandComputedLeverArm) {
  // T_W_C yawed 90 degrees at (1, 2, 3), T_B_C = (I, (0.5, 0, 0.3)):
  // t_C_B = (-0.5, 0, -0.3), t_W_B = Rz(90) t_C_B + t_W_C = (0, -0.5, -0.3) + (1, 2, 3)
  //       = (1, 1.5, 2.7).
  const SE3d T_W_C(expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0)),
                   Eigen::Vector3d(1.0, 2.0, 3.0));
  const InsPositionFactor factor(X(0), Eigen::Vector3d(0.9, 1.6, 2.7), leverArm(), insNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(T_W_C)});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 0.1, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], -0.1, 1e-12);
  EXPECT_NEAR(evaluation.residual[2], 0.0, 1e-12);
}

TEST(InsPositionFactor, ResidualIsZeroForTheFixOfTheTruePose) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_B = test::randomPose(rng, 3.0, 100.0);
    const SE3d T_B_C = test::randomPose(rng, 1.0, 1.0);
    const SE3d T_W_C = T_W_B * T_B_C;
    const InsPositionFactor factor(X(0), T_W_B.t, T_B_C, insNoise());
    const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(T_W_C)});
    EXPECT_LT(evaluation.residual.norm(), 1e-12 * 100.0) << "trial " << trial;
  }
}

TEST(InsPositionFactor, JacobianMatchesNumericTangentDifferences) {
  std::mt19937 rng(22);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_C = test::randomPose(rng, 3.0, 50.0);
    const SE3d T_B_C = test::randomPose(rng, 1.0, 1.5);
    const InsPositionFactor factor(X(0), T_W_C.t + Eigen::Vector3d(0.3, -0.2, 0.1), T_B_C,
                                   insNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {poseBlock(T_W_C)}))
        << "trial " << trial;
  }
}

TEST(InsPositionFactor, RejectsBadArguments) {
  try {
    InsPositionFactor(X(0), Eigen::Vector3d::Zero(), leverArm(), NoiseModel::isotropic(2, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "InsPositionFactor: the noise model has dimension 2, expected 3 (one per "
                 "residual component)");
  }
  try {
    InsPositionFactor(X(0), Eigen::Vector3d::Zero(),
                      SE3d(Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0), Eigen::Vector3d::Zero()),
                      insNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "InsPositionFactor: T_B_C rotation must be a unit quaternion, got norm 2");
  }
  EXPECT_THROW(InsPositionFactor(X(0), Eigen::Vector3d(0.0, std::nan(""), 0.0), leverArm(),
                                 insNoise()),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
