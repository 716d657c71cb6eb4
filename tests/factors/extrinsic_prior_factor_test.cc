#include "factors/extrinsic_prior_factor.h"

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

TEST(ExtrinsicPriorFactor, NamesItsMeasurementAndKey) {
  const ExtrinsicPriorFactor factor(E(0), SE3d(), ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
  EXPECT_EQ(factor.name(), "ExtrinsicPriorFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{E(0)}));
  EXPECT_EQ(factor.robustLoss().kind, RobustLoss::Kind::none);
}

TEST(ExtrinsicPriorFactor, NoiseFromSurveySigmasIsTranslationFirstInMetresAndRadians) {
  const NoiseModel noise = ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05);
  ASSERT_EQ(noise.dimension(), 6);
  EXPECT_TRUE(noise.isDiagonal());
  const double sigma_rad = 2.0 * std::numbers::pi / 180.0;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(noise.sqrtInformation()(i, i), 1.0 / 0.05, 1e-12);
    EXPECT_NEAR(noise.sqrtInformation()(3 + i, 3 + i), 1.0 / sigma_rad, 1e-9);
  }
  try {
    ExtrinsicPriorFactor::noiseFromSigmas(0.0, 0.05);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "ExtrinsicPriorFactor: sigma_rotation_deg must be a positive finite number, got 0");
  }
  EXPECT_THROW(ExtrinsicPriorFactor::noiseFromSigmas(2.0, -1.0), std::invalid_argument);
}

TEST(ExtrinsicPriorFactor, ResidualMatchesHandComputedTranslationAndRotationErrors) {
  // Prior (I, (0.1, 0, 0)); estimate (Rx(0.02), (0.12, 0, -0.01)).
  const ExtrinsicPriorFactor factor(
      E(0), SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.1, 0.0, 0.0)),
      ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
  const auto evaluation = evaluate(
      *factor.createCostFunction(),
      {poseBlock(SE3d(expSO3(Eigen::Vector3d(0.02, 0.0, 0.0)), Eigen::Vector3d(0.12, 0.0, -0.01)))});
  Vector6d expected;
  expected << 0.02, 0.0, -0.01, 0.02, 0.0, 0.0;
  EXPECT_LT((evaluation.residual - expected).norm(), 1e-12);
}

TEST(ExtrinsicPriorFactor, TranslationResidualIsThePlainDifferenceWhateverTheRotation) {
  // Unlike the SE(3) log, a rotation error leaves the translation part alone.
  const SE3d prior(expSO3(Eigen::Vector3d(0.3, -0.2, 1.0)), Eigen::Vector3d(0.1, 0.05, -0.02));
  const SE3d estimate(prior.q * expSO3(Eigen::Vector3d(0.0, 0.4, 0.0)), prior.t);
  const ExtrinsicPriorFactor factor(E(0), prior, ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
  const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(estimate)});
  Vector6d expected;
  expected << 0.0, 0.0, 0.0, 0.0, 0.4, 0.0;
  EXPECT_LT((evaluation.residual - expected).norm(), 1e-12);
}

TEST(ExtrinsicPriorFactor, ResidualIsZeroAtThePrior) {
  std::mt19937 rng(61);
  const SE3d prior = test::randomPose(rng, 3.0, 0.5);
  const ExtrinsicPriorFactor factor(E(0), prior, ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
  EXPECT_LT(evaluate(*factor.createCostFunction(), {poseBlock(prior)}).residual.norm(), 1e-12);
}

TEST(ExtrinsicPriorFactor, JacobianMatchesNumericTangentDifferences) {
  std::mt19937 rng(62);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d prior = test::randomPose(rng, 3.0, 0.5);
    const SE3d T_C_U = prior * test::randomPose(rng, 0.5, 0.1);
    const ExtrinsicPriorFactor factor(E(0), prior,
                                      ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {poseBlock(T_C_U)}))
        << "trial " << trial;
  }
}

}  // namespace
}  // namespace hsmap
