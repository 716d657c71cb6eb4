// Se3Manifold: Ceres' manifold invariants, agreement with se3.h's right
// perturbation T * exp(xi), and the Jacobians against central differences.

#include "solvers/se3_manifold.h"

#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <random>

#include "core/geometry/se3.h"
#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using ceres::Vector;

Vector parametersOf(const SE3d& T) {
  Vector x(7);
  T.toParameters(x.data());
  return x;
}

// Poses whose quaternion has w >= 0, so Plus(x, Minus(y, x)) reproduces y
// with the same sign for any y in the same hemisphere.
SE3d canonical(SE3d T) {
  if (T.q.w() < 0) T.q.coeffs() = -T.q.coeffs();
  return T;
}

TEST(Se3Manifold, SatisfiesCeresManifoldInvariants) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Se3Manifold manifold;
  EXPECT_EQ(manifold.AmbientSize(), 7);
  EXPECT_EQ(manifold.TangentSize(), 6);
  for (int trial = 0; trial < 20; ++trial) {
    const SE3d T_x = canonical(test::randomPose(rng, 3.0));
    Vector delta(6);
    for (int i = 0; i < 6; ++i) delta[i] = 0.3 * normal(rng);
    // y near x (same quaternion hemisphere), rotated by up to ~0.5 rad.
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = 0.3 * normal(rng);
    const SE3d T_y = T_x * SE3d::exp(xi);
    const Vector x = parametersOf(T_x);
    const Vector y = parametersOf(T_y);
    using namespace ceres;  // the macro names Ceres' matchers unqualified
    EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, 1e-9);
  }
}

TEST(Se3Manifold, PlusIsRightMultiplicationByTheSe3Exponential) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Se3Manifold manifold;
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T = test::randomPose(rng, 5.0);
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = normal(rng);
    const Vector x = parametersOf(T);
    Vector result(7);
    ASSERT_TRUE(manifold.Plus(x.data(), xi.data(), result.data()));
    const SE3d expected = T * SE3d::exp(xi);
    const SE3d actual = SE3d::fromParameters(result.data());
    EXPECT_NEAR(actual.q.norm(), 1.0, 1e-15);
    EXPECT_LT((actual.t - expected.t).norm(), 1e-12);
    EXPECT_NEAR(std::abs(actual.q.dot(expected.q)), 1.0, 1e-14);
    // Translation first: a pure rho step moves the origin along the pose's own axes.
    Vector6d pure_translation = Vector6d::Zero();
    pure_translation.head<3>() = Eigen::Vector3d(0.1, -0.2, 0.3);
    ASSERT_TRUE(manifold.Plus(x.data(), pure_translation.data(), result.data()));
    EXPECT_LT((SE3d::fromParameters(result.data()).t -
               (T.t + T.q * Eigen::Vector3d(0.1, -0.2, 0.3)))
                  .norm(),
              1e-12);
  }
}

TEST(Se3Manifold, MinusInvertsPlusAndIgnoresTheQuaternionSign) {
  std::mt19937 rng(13);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Se3Manifold manifold;
  for (int trial = 0; trial < 10; ++trial) {
    const SE3d T = test::randomPose(rng, 2.0);
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi[i] = 0.5 * normal(rng);
    Vector x = parametersOf(T);
    Vector y(7);
    ASSERT_TRUE(manifold.Plus(x.data(), xi.data(), y.data()));
    // -q is the same rotation: the difference must not change.
    Vector y_flipped = y;
    y_flipped.head<4>() *= -1.0;
    Vector6d back, back_flipped;
    ASSERT_TRUE(manifold.Minus(y.data(), x.data(), back.data()));
    ASSERT_TRUE(manifold.Minus(y_flipped.data(), x.data(), back_flipped.data()));
    EXPECT_LT((back - xi).norm(), 1e-11);
    EXPECT_LT((back_flipped - xi).norm(), 1e-11);
  }
}

TEST(Se3Manifold, PlusJacobianMatchesCentralDifferencesInTheTangentSpace) {
  std::mt19937 rng(17);
  const Se3Manifold manifold;
  for (int trial = 0; trial < 10; ++trial) {
    const Vector x = parametersOf(test::randomPose(rng, 4.0));
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> analytic;
    ASSERT_TRUE(manifold.PlusJacobian(x.data(), analytic.data()));
    Eigen::Matrix<double, 7, 6> numeric;
    const double h = 1e-6;
    for (int j = 0; j < 6; ++j) {
      Vector6d step = Vector6d::Zero();
      step[j] = h;
      Vector plus(7), minus(7);
      manifold.Plus(x.data(), step.data(), plus.data());
      step[j] = -h;
      manifold.Plus(x.data(), step.data(), minus.data());
      numeric.col(j) = (plus - minus) / (2 * h);
    }
    EXPECT_LT((numeric - analytic).norm(), 1e-8 * analytic.norm()) << "\n" << numeric << "\n"
                                                                    << analytic;
  }
}

TEST(Se3Manifold, RightMultiplyByPlusJacobianMatchesTheExplicitProduct) {
  std::mt19937 rng(19);
  const Se3Manifold manifold;
  const Vector x = parametersOf(test::randomPose(rng));
  Eigen::Matrix<double, 7, 6, Eigen::RowMajor> J;
  ASSERT_TRUE(manifold.PlusJacobian(x.data(), J.data()));
  Eigen::Matrix<double, 2, 7, Eigen::RowMajor> ambient =
      Eigen::Matrix<double, 2, 7, Eigen::RowMajor>::Random();
  Eigen::Matrix<double, 2, 6, Eigen::RowMajor> tangent;
  ASSERT_TRUE(manifold.RightMultiplyByPlusJacobian(x.data(), 2, ambient.data(), tangent.data()));
  EXPECT_LT((tangent - ambient * J).norm(), 1e-14);
}

}  // namespace
}  // namespace hsmap
