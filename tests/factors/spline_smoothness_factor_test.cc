#include "factors/spline_smoothness_factor.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

NoiseModel smoothnessNoise() { return NoiseModel::isotropic(6, 0.01); }

SE3d translation(double x) { return SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, 0, 0)); }

TEST(SplineSmoothnessFactor, ConnectsThreeConsecutiveControlPoints) {
  const SplineSmoothnessFactor factor(5, smoothnessNoise());
  EXPECT_EQ(factor.name(), "SplineSmoothnessFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{S(4), S(5), S(6)}));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 7, 7}));
  try {
    SplineSmoothnessFactor(0, smoothnessNoise());
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "SplineSmoothnessFactor: control point 0 has no predecessor (i must be >= 1)");
  }
}

TEST(SplineSmoothnessFactor, ResidualIsTheChangeOfIncrementBetweenKnotIntervals) {
  // Steps of 1 m then 2 m along x: r = 1 - 2 = -1 on rho_x.
  const SplineSmoothnessFactor factor(1, smoothnessNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(),
                                   {poseBlock(translation(0.0)), poseBlock(translation(1.0)),
                                    poseBlock(translation(3.0))});
  Vector6d expected;
  expected << -1.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_LT((evaluation.residual - expected).norm(), 1e-12);
}

TEST(SplineSmoothnessFactor, ResidualIsZeroForConstantBodyTwist) {
  std::mt19937 rng(91);
  for (int trial = 0; trial < 5; ++trial) {
    const SE3d start = test::randomPose(rng, 3.0, 20.0);
    Vector6d xi;
    xi << test::randomVector(rng, Eigen::Vector3d::Constant(-1.0), Eigen::Vector3d::Constant(1.0)),
        test::randomVector(rng, Eigen::Vector3d::Constant(-0.5), Eigen::Vector3d::Constant(0.5));
    const SE3d step = SE3d::exp(xi);
    const SplineSmoothnessFactor factor(S(0), S(1), S(2), smoothnessNoise());
    const auto evaluation = evaluate(*factor.createCostFunction(),
                                     {poseBlock(start), poseBlock(start * step),
                                      poseBlock(start * step * step)});
    EXPECT_LT(evaluation.residual.norm(), 1e-11) << "trial " << trial;
  }
}

TEST(SplineSmoothnessFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(92);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d a = test::randomPose(rng, 3.0, 20.0);
    const SE3d b = a * test::randomPose(rng, 0.8, 2.0);
    const SE3d c = b * test::randomPose(rng, 0.8, 2.0);
    const SplineSmoothnessFactor factor(S(0), S(1), S(2), smoothnessNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             {poseBlock(a), poseBlock(b), poseBlock(c)}))
        << "trial " << trial;
  }
}

TEST(SplineSmoothnessFactor, NoiseFromAccelerationSigmasScalesWithTheKnotSpacingSquared) {
  const NoiseModel noise = SplineSmoothnessFactor::noiseFromAccelerationSigmas(0.5, 0.2, 0.1);
  ASSERT_EQ(noise.dimension(), 6);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(noise.sqrtInformation()(i, i), 1.0 / (0.5 * 0.01), 1e-9);
    EXPECT_NEAR(noise.sqrtInformation()(3 + i, 3 + i), 1.0 / (0.2 * 0.01), 1e-9);
  }
  try {
    SplineSmoothnessFactor::noiseFromAccelerationSigmas(0.5, 0.2, 0.0);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "SplineSmoothnessFactor: dt must be a positive finite number, got 0");
  }
}

}  // namespace
}  // namespace hsmap
