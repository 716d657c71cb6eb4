#include "pipelines/simulate/scene/procedural_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hsmap {
namespace {

TEST(ProceduralNoise, VanishesOnTheLattice) {
  for (int i = -3; i <= 3; ++i) {
    for (int j = -3; j <= 3; ++j) {
      EXPECT_EQ(gradientNoise2(9, i, j), 0.0);
      for (int k = 38; k <= 41; ++k) EXPECT_EQ(gradientNoise3(9, i, j, k), 0.0);
    }
  }
}

TEST(ProceduralNoise, IsBoundedZeroMeanAndSpread) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> coordinate(-500.0, 500.0);
  constexpr int kSamples = 200000;
  double sum2 = 0.0, sum3 = 0.0, square2 = 0.0, square3 = 0.0, max2 = 0.0, max3 = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double x = coordinate(rng), y = coordinate(rng), z = coordinate(rng);
    const double n2 = gradientNoise2(11, x, y), n3 = gradientNoise3(11, x, y, z);
    sum2 += n2;
    sum3 += n3;
    square2 += n2 * n2;
    square3 += n3 * n3;
    max2 = std::max(max2, std::abs(n2));
    max3 = std::max(max3, std::abs(n3));
  }
  // The bound sqrt(N)/2 of the header.
  EXPECT_LE(max2, std::sqrt(2.0) / 2.0 + 1e-12);
  EXPECT_LE(max3, std::sqrt(3.0) / 2.0 + 1e-12);
  EXPECT_NEAR(sum2 / kSamples, 0.0, 0.005);
  EXPECT_NEAR(sum3 / kSamples, 0.0, 0.005);
  EXPECT_NEAR(std::sqrt(square2 / kSamples), 0.22, 0.02);
  EXPECT_NEAR(std::sqrt(square3 / kSamples), 0.19, 0.02);
}

TEST(ProceduralNoise, IsAPureFunctionOfSeedAndPosition) {
  const Eigen::Vector3d p(3.217, -1.5, 40.123);
  EXPECT_EQ(gradientNoise3(5, p), gradientNoise3(5, p));
  EXPECT_EQ(gradientNoise3(5, p), gradientNoise3(5, p.x(), p.y(), p.z()));
  // Consecutive seeds give unrelated fields: their correlation over many
  // points is near zero.
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> coordinate(-50.0, 50.0);
  double cross = 0.0, norm_a = 0.0, norm_b = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d q(coordinate(rng), coordinate(rng), coordinate(rng));
    const double a = gradientNoise3(5, q), b = gradientNoise3(6, q);
    cross += a * b;
    norm_a += a * a;
    norm_b += b * b;
  }
  EXPECT_LT(std::abs(cross / std::sqrt(norm_a * norm_b)), 0.03);
}

TEST(ProceduralNoise, IsContinuousAcrossCellBorders) {
  // Across x = 2 (a cell border) the value and the slope match on both sides.
  const double h = 1e-6;
  const double left = gradientNoise3(3, 2.0 - h, 0.3, 0.7);
  const double right = gradientNoise3(3, 2.0 + h, 0.3, 0.7);
  const double centre = gradientNoise3(3, 2.0, 0.3, 0.7);
  EXPECT_NEAR(left, centre, 1e-5);
  EXPECT_NEAR(right, centre, 1e-5);
  const double slope_left = (centre - left) / h;
  const double slope_right = (right - centre) / h;
  EXPECT_NE(slope_left, 0.0);
  EXPECT_NEAR(slope_left, slope_right, 1e-3);
}

TEST(ProceduralNoise, FbmStaysInTheRangeOfOneOctave) {
  const FbmParameters fbm{0.5, 4, 1.98, 0.5};
  double max = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p(0.37 * i, 0.11 * i, 40.0 + 0.003 * i);
    max = std::max(max, std::abs(fbm3(2, p, fbm)));
    max = std::max(max, std::abs(fbm2(2, p.x(), p.y(), fbm)));
  }
  EXPECT_LE(max, std::sqrt(3.0) / 2.0);
  EXPECT_GT(max, 0.3);  // and it is not flat
}

TEST(ProceduralNoise, SmoothStepClampsAndInterpolates) {
  EXPECT_EQ(smoothStep(1.0, 2.0, 0.5), 0.0);
  EXPECT_EQ(smoothStep(1.0, 2.0, 2.5), 1.0);
  EXPECT_DOUBLE_EQ(smoothStep(1.0, 2.0, 1.5), 0.5);
  EXPECT_DOUBLE_EQ(smoothStep(0.0, 4.0, 1.0), 0.15625);  // t = 1/4: t^2 (3 - 2t) = 5/32
}

}  // namespace
}  // namespace hsmap
