#include "core/geometry/se3_bspline_jacobians.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/geometry/se3_bspline.h"
#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

// Four control points of a segment with sizeable relative motion (rotations
// of up to ~0.6 rad between neighbours, so the SE(3) Jacobians are far from I).
std::array<SE3d, 4> wobblySegment(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::array<SE3d, 4> control_points;
  SE3d T(expSO3(Eigen::Vector3d(0.3, -0.5, 2.0)), Eigen::Vector3d(12.0, -4.0, 7.0));
  for (SE3d& control_point : control_points) {
    control_point = T;
    Vector6d step;
    step << 0.5 + 0.3 * unit(rng), 0.3 * unit(rng), 0.2 * unit(rng), 0.35 * unit(rng),
        0.35 * unit(rng), 0.35 * unit(rng);
    T = T * SE3d::exp(step);
  }
  return control_points;
}

// log(T(u)^-1 T(u; control point k moved to T_k exp(delta))): the tangent
// change of the spline pose, as a function of delta.
Eigen::VectorXd poseChange(const std::array<SE3d, 4>& control_points, double u, int k,
                           const Eigen::VectorXd& delta) {
  std::array<SE3d, 4> moved = control_points;
  moved[k] = moved[k] * SE3d::exp(Vector6d(delta));
  const SE3d T = evaluateSe3SplinePose<double>(control_points, u);
  return (T.inverse() * evaluateSe3SplinePose<double>(moved, u)).log();
}

TEST(SE3SplineJacobians, PoseIsBitIdenticalToTheSplineEvaluation) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    const std::array<SE3d, 4> control_points = wobblySegment(rng);
    const double u = std::uniform_real_distribution<double>(-0.3, 1.3)(rng);
    const SE3d expected = evaluateSe3SplinePose<double>(control_points, u);
    const SE3SplineJacobians spline(control_points, u);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(spline.pose().q.coeffs()[i], expected.q.coeffs()[i]);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(spline.pose().t[i], expected.t[i]);
  }
}

TEST(SE3SplineJacobians, FromBlocksReadsTheCeresLayout) {
  std::mt19937 rng(6);
  const std::array<SE3d, 4> control_points = wobblySegment(rng);
  std::array<std::array<double, 7>, 4> storage;
  std::array<const double*, 4> blocks;
  for (int k = 0; k < 4; ++k) {
    control_points[k].toParameters(storage[k].data());
    blocks[k] = storage[k].data();
  }
  const SE3SplineJacobians from_blocks = SE3SplineJacobians::fromBlocks(blocks.data(), 0.4);
  const SE3SplineJacobians direct(control_points, 0.4);
  EXPECT_EQ(from_blocks.pose().t, direct.pose().t);
  EXPECT_EQ(from_blocks.pose().q.coeffs(), direct.pose().q.coeffs());
  const auto J_blocks = from_blocks.controlPointJacobians();
  const auto J_direct = direct.controlPointJacobians();
  for (int k = 0; k < 4; ++k) EXPECT_EQ(J_blocks[k], J_direct[k]) << "control point " << k;
}

TEST(SE3SplineJacobians, AtCoincidentControlPointsTheJacobiansAreTheBSplineBasis) {
  // All four control points equal: every Omega_j = 0, so J_k = (b_k - b_{k+1}) I
  // with the cumulative basis b (b_0 = 1, b_4 = 0), i.e. the uniform cubic
  // B-spline basis functions themselves.
  const SE3d T(expSO3(Eigen::Vector3d(0.4, 0.1, -1.2)), Eigen::Vector3d(1.0, 2.0, 3.0));
  const double u = 0.3;
  const SE3SplineJacobians spline({T, T, T, T}, u);
  const std::array<double, 4> basis = {std::pow(1.0 - u, 3) / 6.0,
                                       (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0,
                                       (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
                                       u * u * u / 6.0};
  const auto J = spline.controlPointJacobians();
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((J[k] - basis[k] * Matrix6d::Identity()).cwiseAbs().maxCoeff(), 1e-15)
        << "control point " << k << ":\n" << J[k];
  }
}

TEST(SE3SplineJacobians, ControlPointJacobiansMatchNumericDifferences) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 10; ++trial) {
    const std::array<SE3d, 4> control_points = wobblySegment(rng);
    // Inside the segment and slightly outside (the polynomial extension).
    const double u = std::uniform_real_distribution<double>(-0.2, 1.2)(rng);
    const auto J = SE3SplineJacobians(control_points, u).controlPointJacobians();
    for (int k = 0; k < 4; ++k) {
      const Eigen::MatrixXd numeric = numericJacobian(
          [&](const Eigen::VectorXd& delta) { return poseChange(control_points, u, k, delta); },
          Eigen::VectorXd::Zero(6));
      EXPECT_LT((J[k] - numeric).cwiseAbs().maxCoeff(), 1e-8)
          << "trial " << trial << ", u " << u << ", control point " << k << "\nJ =\n"
          << J[k] << "\nnumeric =\n" << numeric;
    }
  }
}

TEST(SE3SplineJacobians, LastControlPointHasNoInfluenceAtTheStartOfTheSegment) {
  // b_3(0) = 0: T_{i+3} does not enter the pose at u = 0, exactly.
  std::mt19937 rng(8);
  const auto J = SE3SplineJacobians(wobblySegment(rng), 0.0).controlPointJacobians();
  EXPECT_TRUE(J[3].isZero(0.0)) << J[3];
  EXPECT_FALSE(J[2].isZero(1e-3));
}

TEST(SE3SplineJacobians, MovingAllControlPointsRigidlyMovesThePoseRigidly) {
  // The spline is left-invariant: exp(e) T_k for every k gives exp(e) T(u).
  // As right perturbations, T_k exp(Ad(T_k^-1) e) -> T(u) exp(Ad(T(u)^-1) e),
  // so sum_k J_k Ad(T_k^-1) = Ad(T(u)^-1).
  std::mt19937 rng(9);
  for (int trial = 0; trial < 5; ++trial) {
    const std::array<SE3d, 4> control_points = wobblySegment(rng);
    const double u = 0.1 + 0.2 * trial;
    const SE3SplineJacobians spline(control_points, u);
    const auto J = spline.controlPointJacobians();
    Matrix6d sum = Matrix6d::Zero();
    for (int k = 0; k < 4; ++k) sum += J[k] * control_points[k].inverse().adjoint();
    const Matrix6d expected = spline.pose().inverse().adjoint();
    EXPECT_LT((sum - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff())
        << "trial " << trial;
  }
}

TEST(SE3SplineJacobians, ChainAppliesTheJacobiansFromTheLeft) {
  std::mt19937 rng(10);
  const SE3SplineJacobians spline(wobblySegment(rng), 0.55);
  Eigen::Matrix<double, 2, 6> G;
  G << 1.0, -2.0, 0.5, 3.0, 0.25, -1.0,
       0.0, 4.0, -0.5, 1.5, 2.0, 0.75;
  std::array<Eigen::Matrix<double, 2, 6>, 4> chained;
  spline.chain<2>(G, &chained);
  const auto J = spline.controlPointJacobians();
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((chained[k] - G * J[k]).cwiseAbs().maxCoeff(), 1e-12) << "control point " << k;
  }
}

TEST(SE3SplineJacobians, BodyTwistPerUnitUIsTheKinematicTwistTimesDt) {
  std::mt19937 rng(11);
  const double dt = 0.25;
  for (int trial = 0; trial < 5; ++trial) {
    const std::array<SE3d, 4> control_points = wobblySegment(rng);
    const double u = 0.15 + 0.17 * trial;
    const SE3SplineKinematics<double> kinematics = evaluateSe3SplineKinematics<double>(
        control_points, u, dt, SplineDerivatives::kVelocity);
    Vector6d expected;
    expected << kinematics.linear_velocity_B * dt, kinematics.angular_velocity_B * dt;
    const Vector6d twist = SE3SplineJacobians(control_points, u).bodyTwistPerUnitU();
    EXPECT_LT((twist - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.norm())
        << "trial " << trial;
    // And against differences in u: log(T(u)^-1 T(u + h)) / h.
    const double h = 1e-6;
    const Vector6d numeric =
        (evaluateSe3SplinePose<double>(control_points, u - h).inverse() *
         evaluateSe3SplinePose<double>(control_points, u + h))
            .log() /
        (2.0 * h);
    EXPECT_LT((twist - numeric).cwiseAbs().maxCoeff(), 1e-7 * twist.norm()) << "trial " << trial;
  }
}

}  // namespace
}  // namespace hsmap
