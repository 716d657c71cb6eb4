#include "factors/reprojection_factor.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "core/graph/key.h"
#include "factors/reprojection_with_intrinsics_factor.h"
#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;
using test::vectorBlock;

PinholeRadtanParameters undistortedCamera() { return test::pinholeTestCamera(); }

PinholeRadtanParameters distortedCamera() {
  PinholeRadtanParameters p = undistortedCamera();
  p.fy = 780.0;
  p.distortion = {-0.12, 0.05, 0.001, -0.0005, 0.01};
  return p;
}

Eigen::VectorXd intrinsicsVector(const PinholeRadtanParameters& p) {
  const std::array<double, PinholeRadtanCamera::kNumIntrinsics> k = PinholeRadtanCamera(p).intrinsics();
  return Eigen::Map<const Eigen::VectorXd>(k.data(), k.size());
}

NoiseModel pixelNoise() { return NoiseModel::isotropic(2, 1.0); }

// A landmark in front of a random camera: (T_W_C, p_W, p_C).
struct Sighting {
  SE3d T_W_C;
  Eigen::Vector3d p_W;
  Eigen::Vector3d p_C;
};

Sighting randomSighting(std::mt19937& rng) {
  Sighting s;
  s.T_W_C = test::randomPose(rng, 2.0, 20.0);
  s.p_C = test::randomVector(rng, Eigen::Vector3d(-1.0, -0.7, 2.0), Eigen::Vector3d(1.0, 0.7, 8.0));
  s.p_W = s.T_W_C * s.p_C;
  return s;
}

TEST(ReprojectionFactor, NamesItsMeasurementAndKeysInResidualOrder) {
  const ReprojectionFactor factor(X(3), L(17), Eigen::Vector2d(10.0, 20.0), distortedCamera(),
                                  pixelNoise(), RobustLoss::huber(1.5));
  EXPECT_EQ(factor.name(), "ReprojectionFactor");
  ASSERT_EQ(factor.keys().size(), 2u);
  EXPECT_EQ(factor.keys()[0], X(3));
  EXPECT_EQ(factor.keys()[1], L(17));
  EXPECT_EQ(factor.residualDimension(), 2);
  EXPECT_EQ(factor.robustLoss().toString(), "huber(1.5)");
  const auto cost = factor.createCostFunction();
  EXPECT_EQ(cost->num_residuals(), 2);
  EXPECT_EQ(cost->parameter_block_sizes(), (std::vector<int32_t>{7, 3}));
}

TEST(ReprojectionFactor, ResidualMatchesHandComputedPixelError) {
  // Identity pose, p_C = p_W = (0.1, -0.2, 2): x = 0.05, y = -0.1,
  // u = 800 * 0.05 + 480 = 520, v = 700 * -0.1 + 270 = 200.
  const ReprojectionFactor factor(X(0), L(0), Eigen::Vector2d(515.0, 203.0), undistortedCamera(),
                                  pixelNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(),
                                   {poseBlock(SE3d()), vectorBlock(Eigen::Vector3d(0.1, -0.2, 2.0))});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 5.0, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], -3.0, 1e-12);
}

TEST(ReprojectionFactor, ResidualUsesTheInverseOfThePose) {
  // Camera at (0, 0, -2) looking along +z (identity rotation), yawed 90
  // degrees about its optical axis: the world point (0, 1, 0) is at
  // p_C = R^T (p_W - t) = (1, 0, 2), so u = 800 * 0.5 + 480 = 880, v = 270.
  const SE3d T_W_C(expSO3(Eigen::Vector3d(0.0, 0.0, std::acos(-1.0) / 2.0)),
                   Eigen::Vector3d(0.0, 0.0, -2.0));
  const ReprojectionFactor factor(X(0), L(0), Eigen::Vector2d(880.0, 270.0), undistortedCamera(),
                                  pixelNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(),
                                   {poseBlock(T_W_C), vectorBlock(Eigen::Vector3d(0.0, 1.0, 0.0))});
  EXPECT_NEAR(evaluation.residual[0], 0.0, 1e-10);
  EXPECT_NEAR(evaluation.residual[1], 0.0, 1e-10);
}

TEST(ReprojectionFactor, ResidualIsZeroAtTheTrueState) {
  std::mt19937 rng(11);
  const PinholeRadtanCamera camera(distortedCamera());
  for (int trial = 0; trial < 20; ++trial) {
    const Sighting s = randomSighting(rng);
    const ReprojectionFactor factor(X(0), L(0), camera.project(s.p_C), distortedCamera(),
                                    pixelNoise());
    const auto evaluation =
        evaluate(*factor.createCostFunction(), {poseBlock(s.T_W_C), vectorBlock(s.p_W)});
    ASSERT_TRUE(evaluation.ok);
    EXPECT_LT(evaluation.residual.norm(), 1e-8) << "trial " << trial;
  }
}

TEST(ReprojectionFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(12);
  std::normal_distribution<double> pixel_noise(0.0, 5.0);
  const PinholeRadtanCamera camera(distortedCamera());
  for (int trial = 0; trial < 20; ++trial) {
    const Sighting s = randomSighting(rng);
    const Eigen::Vector2d pixel =
        camera.project(s.p_C) + Eigen::Vector2d(pixel_noise(rng), pixel_noise(rng));
    const ReprojectionFactor factor(X(0), L(0), pixel, distortedCamera(), pixelNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                             {poseBlock(s.T_W_C), vectorBlock(s.p_W)}))
        << "trial " << trial;
  }
}

TEST(ReprojectionFactor, PointsBehindTheCameraGiveFiniteResidualsThatPullThemForward) {
  const ReprojectionFactor factor(X(0), L(0), Eigen::Vector2d(480.0, 270.0), undistortedCamera(),
                                  pixelNoise());
  const auto cost = factor.createCostFunction();
  double previous_norm = 0.0;
  // The same lateral offset ever further behind the camera: finite, and the
  // residual grows the further behind the point is (so descent moves it forward).
  for (double z : {0.0, -0.5, -3.0, -50.0}) {
    const auto evaluation =
        evaluate(*cost, {poseBlock(SE3d()), vectorBlock(Eigen::Vector3d(0.2, -0.1, z))});
    ASSERT_TRUE(evaluation.ok);
    ASSERT_TRUE(evaluation.residual.allFinite()) << "z = " << z;
    for (const auto& J : evaluation.jacobians) ASSERT_TRUE(J.allFinite()) << "z = " << z;
    EXPECT_GT(evaluation.residual.norm(), previous_norm) << "z = " << z;
    previous_norm = evaluation.residual.norm();
    // d |r|^2 / d z < 0: moving the point forward reduces the error.
    const Eigen::Vector3d gradient = evaluation.jacobians[1].transpose() * evaluation.residual;
    EXPECT_LT(gradient.z(), 0.0) << "z = " << z;
  }
}

TEST(ReprojectionFactor, RejectsAWrongNoiseDimension) {
  try {
    ReprojectionFactor(X(0), L(0), Eigen::Vector2d(1.0, 2.0), undistortedCamera(),
                       NoiseModel::isotropic(3, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "ReprojectionFactor: the noise model has dimension 3, expected 2 (one per "
                 "residual component)");
  }
}

TEST(ReprojectionFactor, RejectsANonFinitePixelAndInvalidIntrinsics) {
  EXPECT_THROW(ReprojectionFactor(X(0), L(0), Eigen::Vector2d(std::nan(""), 2.0),
                                  undistortedCamera(), pixelNoise()),
               std::invalid_argument);
  PinholeRadtanParameters bad = undistortedCamera();
  bad.fx = -1.0;
  EXPECT_THROW(ReprojectionFactor(X(0), L(0), Eigen::Vector2d(1.0, 2.0), bad, pixelNoise()),
               std::invalid_argument);
}

TEST(ReprojectionWithIntrinsicsFactor, NamesItsMeasurementAndKeysInResidualOrder) {
  const ReprojectionWithIntrinsicsFactor factor(X(2), L(5), K(1), Eigen::Vector2d(1.0, 2.0),
                                                pixelNoise());
  EXPECT_EQ(factor.name(), "ReprojectionWithIntrinsicsFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{X(2), L(5), K(1)}));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(),
            (std::vector<int32_t>{7, 3, 9}));
}

TEST(ReprojectionWithIntrinsicsFactor, ResidualMatchesHandComputedPixelError) {
  // As the fixed-intrinsics case, with k1 = 0.1: r2 = 0.0125, radial = 1.00125,
  // u = 800 * 0.05 * 1.00125 + 480 = 520.05, v = 700 * -0.1 * 1.00125 + 270 = 199.9125.
  PinholeRadtanParameters p = undistortedCamera();
  p.distortion[0] = 0.1;
  const ReprojectionWithIntrinsicsFactor factor(X(0), L(0), K(0), Eigen::Vector2d(515.0, 203.0),
                                                pixelNoise());
  const auto evaluation =
      evaluate(*factor.createCostFunction(), {poseBlock(SE3d()),
                                              vectorBlock(Eigen::Vector3d(0.1, -0.2, 2.0)),
                                              vectorBlock(intrinsicsVector(p))});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 5.05, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], -3.0875, 1e-12);
}

TEST(ReprojectionWithIntrinsicsFactor, AgreesWithTheFixedIntrinsicsFactor) {
  std::mt19937 rng(13);
  for (int trial = 0; trial < 5; ++trial) {
    const Sighting s = randomSighting(rng);
    const Eigen::Vector2d pixel(400.0 + 10.0 * trial, 300.0 - 7.0 * trial);
    const ReprojectionFactor fixed(X(0), L(0), pixel, distortedCamera(), pixelNoise());
    const ReprojectionWithIntrinsicsFactor free(X(0), L(0), K(0), pixel, pixelNoise());
    const auto a = evaluate(*fixed.createCostFunction(), {poseBlock(s.T_W_C), vectorBlock(s.p_W)});
    const auto b = evaluate(*free.createCostFunction(),
                            {poseBlock(s.T_W_C), vectorBlock(s.p_W),
                             vectorBlock(intrinsicsVector(distortedCamera()))});
    EXPECT_LT((a.residual - b.residual).norm(), 1e-12);
    EXPECT_LT((a.jacobians[0] - b.jacobians[0]).norm(), 1e-9);
    EXPECT_LT((a.jacobians[1] - b.jacobians[1]).norm(), 1e-9);
  }
}

TEST(ReprojectionWithIntrinsicsFactor, JacobiansMatchNumericTangentDifferences) {
  std::mt19937 rng(14);
  for (int trial = 0; trial < 20; ++trial) {
    const Sighting s = randomSighting(rng);
    const ReprojectionWithIntrinsicsFactor factor(X(0), L(0), K(0),
                                                  Eigen::Vector2d(300.0, 250.0), pixelNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(
        *factor.createCostFunction(),
        {poseBlock(s.T_W_C), vectorBlock(s.p_W), vectorBlock(intrinsicsVector(distortedCamera()))}))
        << "trial " << trial;
  }
}

TEST(ReprojectionWithIntrinsicsFactor, RejectsAWrongNoiseDimension) {
  try {
    ReprojectionWithIntrinsicsFactor(X(0), L(0), K(0), Eigen::Vector2d(1.0, 2.0),
                                     NoiseModel::isotropic(1, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "ReprojectionWithIntrinsicsFactor: the noise model has dimension 1, expected 2 "
                 "(one per residual component)");
  }
}

}  // namespace
}  // namespace hsmap
