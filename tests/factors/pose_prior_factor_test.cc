#include "factors/pose_prior_factor.h"

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

NoiseModel poseNoise() { return NoiseModel::isotropic(6, 0.1); }

TEST(PosePriorFactor, NamesItsMeasurementAndKey) {
  const PosePriorFactor factor(S(0), SE3d(), poseNoise());
  EXPECT_EQ(factor.name(), "PosePriorFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(0)}));
  EXPECT_EQ(factor.residualDimension(), 6);
}

TEST(PosePriorFactor, ResidualIsTranslationFirstThenRotation) {
  // Pure translation: log = [t; 0].  Pure rotation: log = [0; phi].
  const PosePriorFactor factor(X(0), SE3d(), poseNoise());
  const auto cost = factor.createCostFunction();
  const auto translated = evaluate(*cost, {poseBlock(SE3d(Eigen::Quaterniond::Identity(),
                                                          Eigen::Vector3d(1.0, 2.0, 3.0)))});
  Vector6d expected;
  expected << 1.0, 2.0, 3.0, 0.0, 0.0, 0.0;
  EXPECT_LT((translated.residual - expected).norm(), 1e-12);
  const auto rotated = evaluate(
      *cost, {poseBlock(SE3d(expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0)),
                             Eigen::Vector3d::Zero()))});
  expected << 0.0, 0.0, 0.0, 0.0, 0.0, std::numbers::pi / 2.0;
  EXPECT_LT((rotated.residual - expected).norm(), 1e-12);
}

TEST(PosePriorFactor, ResidualRecoversTheRightPerturbationOfThePrior) {
  std::mt19937 rng(41);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d prior = test::randomPose(rng, 3.0, 10.0);
    Vector6d xi;
    xi << test::randomVector(rng, Eigen::Vector3d::Constant(-0.5), Eigen::Vector3d::Constant(0.5)),
        test::randomVector(rng, Eigen::Vector3d::Constant(-0.4), Eigen::Vector3d::Constant(0.4));
    const PosePriorFactor factor(X(0), prior, poseNoise());
    const auto cost = factor.createCostFunction();
    EXPECT_LT(evaluate(*cost, {poseBlock(prior)}).residual.norm(), 1e-12);
    EXPECT_LT((evaluate(*cost, {poseBlock(prior * SE3d::exp(xi))}).residual - xi).norm(), 1e-10)
        << "trial " << trial;
  }
}

TEST(PosePriorFactor, JacobianMatchesNumericTangentDifferences) {
  std::mt19937 rng(42);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d prior = test::randomPose(rng, 3.0, 10.0);
    const SE3d T = prior * test::randomPose(rng, 1.5, 2.0);
    const PosePriorFactor factor(X(0), prior, poseNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {poseBlock(T)}))
        << "trial " << trial;
  }
}

TEST(PosePriorFactor, RejectsAWrongNoiseDimension) {
  try {
    PosePriorFactor(X(0), SE3d(), NoiseModel::isotropic(3, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "PosePriorFactor: the noise model has dimension 3, expected 6 (one per residual "
                 "component)");
  }
}

}  // namespace
}  // namespace hsmap
