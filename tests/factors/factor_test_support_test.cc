// Checks the tangent-space machinery the factor tests rely on, so that a
// Jacobian test cannot pass because of a wrong plus-Jacobian.
#include "tests/factors/factor_test_support.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

namespace hsmap::test {
namespace {

TEST(FactorTestSupport, PlusJacobianOfPoseMatchesNumericDerivativeOfRightPerturbation) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    const ParameterBlock block = poseBlock(randomPose(rng, 2.5, 10.0));
    const Eigen::MatrixXd P = plusJacobian(block);
    ASSERT_EQ(P.rows(), 7);
    ASSERT_EQ(P.cols(), 6);
    const double h = 1e-6;
    for (int k = 0; k < 6; ++k) {
      const ParameterBlock forward = plus(block, h * Eigen::VectorXd::Unit(6, k));
      const ParameterBlock backward = plus(block, -h * Eigen::VectorXd::Unit(6, k));
      for (int i = 0; i < 7; ++i) {
        const double numeric = (forward.values[i] - backward.values[i]) / (2.0 * h);
        EXPECT_NEAR(P(i, k), numeric, 1e-8) << "row " << i << " column " << k;
      }
    }
  }
}

TEST(FactorTestSupport, RightPerturbationActsInTheBodyFrame) {
  // T exp([rho; 0]) moves the origin by R rho: a perturbation along the
  // body's x axis of a pose yawed by 90 degrees moves it along world y.
  const SE3d T(expSO3(Eigen::Vector3d(0.0, 0.0, std::numbers::pi / 2.0)), Eigen::Vector3d(1.0, 2.0, 3.0));
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(6);
  delta[0] = 0.5;
  const ParameterBlock moved = plus(poseBlock(T), delta);
  EXPECT_NEAR(moved.values[4], 1.0, 1e-12);
  EXPECT_NEAR(moved.values[5], 2.5, 1e-12);
  EXPECT_NEAR(moved.values[6], 3.0, 1e-12);
}

TEST(FactorTestSupport, EuclideanBlocksArePerturbedByAddition) {
  const ParameterBlock block = vectorBlock(Eigen::Vector3d(1.0, 2.0, 3.0));
  const ParameterBlock moved = plus(block, Eigen::Vector3d(0.1, 0.0, -0.2));
  EXPECT_DOUBLE_EQ(moved.values[0], 1.1);
  EXPECT_DOUBLE_EQ(moved.values[2], 2.8);
  EXPECT_TRUE(plusJacobian(block).isIdentity());
}

}  // namespace
}  // namespace hsmap::test
