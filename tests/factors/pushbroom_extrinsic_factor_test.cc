#include "factors/pushbroom_extrinsic_factor.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"
#include "tests/support/uhi_camera.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::poseBlock;
using test::tangentJacobiansMatchNumeric;

PushbroomParameters uhiCamera() { return testing::presetUhiCamera(); }

NoiseModel lineNoise() {
  Eigen::Vector2d sigmas(1.0, 0.5 / 1500.0);
  return NoiseModel::fromSigmas(sigmas);
}

// A point on the scan plane of the line (y_U = 0), 2 m ahead, seen at sample u.
struct SeenPoint {
  Eigen::Vector3d p_W;
  double u;
};
SeenPoint pointOnLine(const SE3d& T_W_C, const SE3d& T_C_U, double x_U) {
  const Eigen::Vector3d p_U(x_U, 0.0, 2.0);
  const PushbroomCamera camera(uhiCamera());
  return {T_W_C * T_C_U * p_U, camera.project(p_U).x()};
}

TEST(PushbroomExtrinsicFactor, NamesItsMeasurementAndKey) {
  const PushbroomExtrinsicFactor factor(E(0), SE3d(), Eigen::Vector3d(0, 0, 2), 962.0, uhiCamera(),
                                        lineNoise(), RobustLoss::huber(2.0));
  EXPECT_EQ(factor.name(), "PushbroomExtrinsicFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{E(0)}));
  EXPECT_EQ(factor.robustLoss().kind, RobustLoss::Kind::huber);
}

TEST(PushbroomExtrinsicFactor, ResidualIsZeroForThePointTheLineSees) {
  std::mt19937 rng(71);
  for (int trial = 0; trial < 5; ++trial) {
    const SE3d T_W_C = test::randomPose(rng, 3.0, 20.0);
    const SE3d T_C_U = test::randomPose(rng, 0.1, 0.1);
    const SeenPoint seen = pointOnLine(T_W_C, T_C_U, 0.3 * trial - 0.6);
    const PushbroomExtrinsicFactor factor(E(0), T_W_C, seen.p_W, seen.u, uhiCamera(), lineNoise());
    EXPECT_LT(evaluate(*factor.createCostFunction(), {poseBlock(T_C_U)}).residual.norm(), 1e-9);
  }
}

TEST(PushbroomExtrinsicFactor, AcrossLineResidualIsTheTangentOfTheOffset) {
  // The point 1 cm across the line at 2 m depth: r = (0, 0.005).
  const PushbroomExtrinsicFactor factor(E(0), SE3d(), Eigen::Vector3d(0.0, 0.01, 2.0), 962.0,
                                        uhiCamera(), lineNoise());
  const auto evaluation = evaluate(*factor.createCostFunction(), {poseBlock(SE3d())});
  EXPECT_NEAR(evaluation.residual[0], 0.0, 1e-12);
  EXPECT_NEAR(evaluation.residual[1], 0.005, 1e-12);
}

TEST(PushbroomExtrinsicFactor, JacobianMatchesNumericTangentDifferences) {
  std::mt19937 rng(72);
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T_W_C = test::randomPose(rng, 3.0, 20.0);
    const SE3d T_C_U_true = test::randomPose(rng, 0.1, 0.1);
    const SeenPoint seen = pointOnLine(T_W_C, T_C_U_true, 0.2 * trial - 1.0);
    const SE3d T_C_U = T_C_U_true * test::randomPose(rng, 0.05, 0.05);
    const PushbroomExtrinsicFactor factor(E(0), T_W_C, seen.p_W, seen.u + 3.0, uhiCamera(),
                                          lineNoise());
    EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {poseBlock(T_C_U)}))
        << "trial " << trial;
  }
}

TEST(PushbroomExtrinsicFactor, RejectsBadArguments) {
  EXPECT_THROW(PushbroomExtrinsicFactor(E(0), SE3d(), Eigen::Vector3d(0, 0, 2), 1.0, uhiCamera(),
                                        NoiseModel::isotropic(3, 1.0)),
               std::invalid_argument);
  EXPECT_THROW(PushbroomExtrinsicFactor(E(0), SE3d(), Eigen::Vector3d(0, NAN, 2), 1.0, uhiCamera(),
                                        lineNoise()),
               std::invalid_argument);
  PushbroomParameters bad = uhiCamera();
  bad.f = 0.0;
  EXPECT_THROW(
      PushbroomExtrinsicFactor(E(0), SE3d(), Eigen::Vector3d(0, 0, 2), 1.0, bad, lineNoise()),
      std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
