#include "core/geometry/se3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

Eigen::Matrix4d hat4(const Vector6d& xi) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.topLeftCorner<3, 3>() = hat(xi.tail<3>());
  m.topRightCorner<3, 1>() = xi.head<3>();
  return m;
}

// Tangent vectors whose rotation part spans zero, the Taylor branch, its
// boundary (|phi| = 1e-2) and large angles.
std::vector<Vector6d> testTwists() {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::vector<Vector6d> out;
  for (double angle : {0.0, 1e-7, 4e-3, 9.9e-3, 1.01e-2, 0.4, 1.5, 3.0}) {
    Vector6d xi;
    for (int i = 0; i < 6; ++i) xi(i) = normal(rng);
    xi.tail<3>() = xi.tail<3>().normalized() * angle;
    out.push_back(xi);
  }
  return out;
}

SE3d randomPose(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Vector6d xi;
  for (int i = 0; i < 6; ++i) xi(i) = normal(rng);
  return SE3d::exp(xi);
}

double poseDistance(const SE3d& a, const SE3d& b) {
  return (a.t - b.t).norm() + a.q.angularDistance(b.q);
}

TEST(Se3, ActionCompositionAndInverseAgreeWithMatrices) {
  std::mt19937 rng(1);
  const SE3d a = randomPose(rng), b = randomPose(rng);
  const Eigen::Vector3d p(0.3, -2.0, 5.0);
  EXPECT_LT(((a * b).matrix() - a.matrix() * b.matrix()).norm(), 1e-14);
  EXPECT_LT((a.inverse().matrix() - a.matrix().inverse()).norm(), 1e-13);
  EXPECT_LT((a * p - (a.matrix() * p.homogeneous()).head<3>()).norm(), 1e-14);
  EXPECT_LT(((a * a.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-14);
  EXPECT_EQ(SE3d::identity() * p, p);
  EXPECT_LT(poseDistance(SE3d::fromMatrix(a.matrix()), a), 1e-14);
}

TEST(Se3, ExpMatchesTheMatrixExponential) {
  for (const Vector6d& xi : testTwists()) {
    const Eigen::Matrix4d expected = hat4(xi).exp();
    EXPECT_LT((SE3d::exp(xi).matrix() - expected).norm(), 1e-13) << xi.transpose();
  }
}

TEST(Se3, LogInvertsExp) {
  for (const Vector6d& xi : testTwists()) {
    EXPECT_LT((SE3d::exp(xi).log() - xi).norm(), 1e-12 * (1.0 + xi.norm())) << xi.transpose();
  }
}

TEST(Se3, AdjointConjugatesTwists) {
  std::mt19937 rng(2);
  const SE3d T = randomPose(rng);
  for (const Vector6d& xi : testTwists()) {
    const SE3d lhs = T * SE3d::exp(xi) * T.inverse();
    const SE3d rhs = SE3d::exp(T.adjoint() * xi);
    EXPECT_LT(poseDistance(lhs, rhs), 1e-12) << xi.transpose();
    EXPECT_LT((T.adjointTimes(xi) - T.adjoint() * xi).norm(), 1e-13);
  }
}

TEST(Se3, LieBracketIsTheMatrixCommutator) {
  const std::vector<Vector6d> twists = testTwists();
  const Vector6d& a = twists[5];
  const Vector6d& b = twists[6];
  const Eigen::Matrix4d commutator = hat4(a) * hat4(b) - hat4(b) * hat4(a);
  EXPECT_LT((hat4(lieBracketSE3(a, b)) - commutator).norm(), 1e-14);
}

TEST(Se3, ParameterBlockIsEigenQuaternionOrderThenTranslation) {
  std::mt19937 rng(4);
  const SE3d T = randomPose(rng);
  double block[SE3d::kNumParameters];
  T.toParameters(block);
  const Eigen::Map<const Eigen::Quaterniond> q_in_place(block);
  EXPECT_EQ(q_in_place.coeffs(), T.q.coeffs());
  EXPECT_EQ(Eigen::Map<const Eigen::Vector3d>(block + 4), T.t);
  const SE3d back = SE3d::fromParameters(block);
  EXPECT_EQ(back.q.coeffs(), T.q.coeffs());
  EXPECT_EQ(back.t, T.t);
}

TEST(Se3, ActionJacobiansMatchNumericDifferentiation) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const SE3d T = randomPose(rng);
    const Eigen::Vector3d p(0.4 * trial - 1.0, 2.0, -0.7 + trial);
    const Eigen::MatrixXd numeric_pose = numericJacobian(
        [&](const Eigen::VectorXd& delta) -> Eigen::VectorXd {
          return (T * SE3d::exp(Vector6d(delta))) * p;
        },
        Eigen::VectorXd::Zero(6));
    // Rounding in the central difference is ~eps |T p| / h.
    EXPECT_LT((T.jacobianOfActionWrtPose(p) - numeric_pose).norm(), 1e-9 * (1.0 + (T * p).norm()));
    const Eigen::MatrixXd numeric_point = numericJacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return T * Eigen::Vector3d(x); }, p);
    EXPECT_LT((T.jacobianOfActionWrtPoint() - numeric_point).norm(), 1e-9);
  }
}

TEST(Se3, RightAndLeftJacobiansMatchNumericDifferentiation) {
  for (const Vector6d& xi : testTwists()) {
    const SE3d T = SE3d::exp(xi);
    const Eigen::MatrixXd right = numericJacobian(
        [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
          return (T.inverse() * SE3d::exp(Vector6d(xi + d))).log();
        },
        Eigen::VectorXd::Zero(6));
    EXPECT_LT((SE3d::rightJacobian(xi) - right).norm(), 1e-9) << xi.transpose();
    const Eigen::MatrixXd left = numericJacobian(
        [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
          return (SE3d::exp(Vector6d(xi + d)) * T.inverse()).log();
        },
        Eigen::VectorXd::Zero(6));
    EXPECT_LT((SE3d::leftJacobian(xi) - left).norm(), 1e-9) << xi.transpose();
  }
}

TEST(Se3, JacobianInversesAreInverses) {
  for (const Vector6d& xi : testTwists()) {
    EXPECT_LT((SE3d::rightJacobian(xi) * SE3d::rightJacobianInverse(xi) - Matrix6d::Identity())
                  .norm(),
              1e-11)
        << xi.transpose();
    EXPECT_LT((SE3d::leftJacobian(xi) * SE3d::leftJacobianInverse(xi) - Matrix6d::Identity())
                  .norm(),
              1e-11)
        << xi.transpose();
  }
}

TEST(Se3, LogDerivativeUnderRightPerturbationIsInverseRightJacobian) {
  for (const Vector6d& xi : testTwists()) {
    const SE3d T = SE3d::exp(xi);
    const Eigen::MatrixXd numeric = numericJacobian(
        [&](const Eigen::VectorXd& delta) -> Eigen::VectorXd {
          return (T * SE3d::exp(Vector6d(delta))).log();
        },
        Eigen::VectorXd::Zero(6));
    EXPECT_LT((SE3d::rightJacobianInverse(T.log()) - numeric).norm(), 1e-9) << xi.transpose();
  }
}

TEST(Se3, InterpolationHasConstantBodyTwist) {
  std::mt19937 rng(6);
  const SE3d a = randomPose(rng), b = randomPose(rng);
  EXPECT_LT(poseDistance(SE3d::interpolate(a, b, 0.0), a), 1e-14);
  EXPECT_LT(poseDistance(SE3d::interpolate(a, b, 1.0), b), 1e-12);
  // Going half way twice from a lands on b.
  const SE3d half = SE3d::interpolate(a, b, 0.5);
  const SE3d step = a.inverse() * half;
  EXPECT_LT(poseDistance(a * step * step, b), 1e-12);
}

// The same code with Jets: the derivative of (T exp(delta)) p at delta = 0 is
// the analytic action Jacobian, and d log(exp(delta)) / d delta at exactly zero
// (Taylor branches everywhere) is the identity.
TEST(Se3, JetEvaluationGivesTheAnalyticJacobians) {
  using Jet = ceres::Jet<double, 6>;
  std::mt19937 rng(8);
  const SE3d T = randomPose(rng);
  const Eigen::Vector3d p(1.0, -0.5, 3.0);
  Vector6<Jet> delta;
  for (int i = 0; i < 6; ++i) delta(i) = Jet(0.0, i);
  const Vector3<Jet> moved = (T.cast<Jet>() * SE3<Jet>::exp(delta)) * p.cast<Jet>();
  const Eigen::Matrix<double, 3, 6> analytic = T.jacobianOfActionWrtPose(p);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(moved(r).a, (T * p)(r), 1e-14);
    EXPECT_LT((moved(r).v.transpose() - analytic.row(r)).norm(), 1e-13);
  }
  const Vector6<Jet> log_of_exp = SE3<Jet>::exp(delta).log();
  for (int r = 0; r < 6; ++r) {
    EXPECT_EQ(log_of_exp(r).a, 0.0);
    EXPECT_LT((log_of_exp(r).v - Vector6d::Unit(r)).norm(), 1e-15);
  }
}

}  // namespace
}  // namespace hsmap
