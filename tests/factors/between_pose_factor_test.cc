#include "factors/between_pose_factor.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

NoiseModel poseNoise() { return NoiseModel::isotropic(6, 0.1); }

TEST(BetweenPoseFactor, NamesItsMeasurementAndKeysInOrder) {
  const BetweenPoseFactor factor(X(1), X(2), SE3d(), poseNoise());
  EXPECT_EQ(factor.name(), "BetweenPoseFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{X(1), X(2)}));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(), (std::vector<int32_t>{7, 7}));
}

TEST(BetweenPoseFactor, ResidualMatchesHandComputedRelativeTranslation) {
  // T_W_A at x = 1, T_W_B at x = 3: T_A_B = (I, (2, 0, 0)); measured 1.5.
  const BetweenPoseFactor factor(X(0), X(1),
                                 SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.5, 0, 0)),
                                 poseNoise());
  const auto evaluation = evaluate(
      *factor.createCostFunction(),
      {poseBlock(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(1.0, 0.0, 0.0))),
       poseBlock(SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(3.0, 0.0, 0.0)))});
  Vector6d expected;
  expected << 0.5, 0.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT((evaluation.residual - expected).norm(), 1e-12);
}

TEST(BetweenPoseFactor, ResidualIsZeroForTheTrueRelativePoseAndRecoversAPerturbation) {
  std::mt19937 rng(51);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_A = test::randomPose(rng, 3.0, 20.0);
    const SE3d T_A_B = test::randomPose(rng, 1.0, 3.0);
    const BetweenPoseFactor factor(X(0), X(1), T_A_B, poseNoise());
    const auto cost = factor.createCostFunction();
    EXPECT_LT(evaluate(*cost, {poseBlock(T_W_A), poseBlock(T_W_A * T_A_B)}).residual.norm(), 1e-11);
    Vector6d xi;
    xi << 0.1, -0.2, 0.05, 0.03, 0.2, -0.1;
    EXPECT_LT(
        (evaluate(*cost, {poseBlock(T_W_A), poseBlock(T_W_A * T_A_B * SE3d::exp(xi))}).residual -
         xi)
            .norm(),
        1e-10);
  }
}

TEST(BetweenPoseFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(52);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_A = test::randomPose(rng, 3.0, 20.0);
    const SE3d T_W_B = T_W_A * test::randomPose(rng, 1.5, 3.0);
    const BetweenPoseFactor factor(X(0), X(1), test::randomPose(rng, 1.5, 3.0), poseNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             {poseBlock(T_W_A), poseBlock(T_W_B)}))
        << "trial " << trial;
  }
}

TEST(BetweenPoseFactor, RejectsAMeasurementThatIsNotARotation) {
  try {
    BetweenPoseFactor(X(0), X(1), SE3d(Eigen::Quaterniond(1.0, 1.0, 0.0, 0.0), Eigen::Vector3d::Zero()),
                      poseNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "BetweenPoseFactor: measured T_A_B rotation must be a unit quaternion, got norm "
                 "1.4142135623730951");
  }
}

}  // namespace
}  // namespace hsmap
