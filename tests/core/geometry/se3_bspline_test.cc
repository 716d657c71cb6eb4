#include "core/geometry/se3_bspline.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

constexpr double kT0 = 2.0;
constexpr double kDt = 0.1;

Vector6d constantTwist() {
  Vector6d xi;
  xi << 0.8, -0.3, 0.25, 0.4, -0.7, 1.1;  // [v_B; omega_B]
  return xi;
}

SE3d startPose() {
  Vector6d xi;
  xi << 3.0, -1.0, 12.0, 0.3, -0.2, 2.0;
  return SE3d::exp(xi);
}

// T(t) = T0 exp(t xi) is reproduced exactly when control point k is
// T0 exp((t0 + (k - 1) dt) xi): every Omega_j = dt xi, the cumulative basis
// sums to 1 + u, so T(u) = T_i exp((1 + u) dt xi) = T0 exp(t xi).
SE3Splined constantTwistSpline(int num_control_points) {
  std::vector<SE3d> control_points;
  for (int k = 0; k < num_control_points; ++k) {
    control_points.push_back(startPose() *
                             SE3d::exp(Vector6d((kT0 + (k - 1) * kDt) * constantTwist())));
  }
  return SE3Splined(kT0, kDt, control_points);
}

// A helix with a rotation that varies on all three axes.
SE3d helixPose(double t) {
  const Eigen::Vector3d p(4.0 * std::cos(0.7 * t), 4.0 * std::sin(0.7 * t), 0.5 * t);
  const Eigen::Vector3d phi(0.3 * std::sin(1.3 * t), 0.2 * std::cos(0.9 * t), 0.7 * t + 0.1);
  return SE3d(expSO3(phi), p);
}

SE3Splined helixSpline() {
  std::vector<SE3d> control_points;
  for (int k = 0; k < 40; ++k) control_points.push_back(helixPose(kT0 + (k - 1) * kDt));
  return SE3Splined(kT0, kDt, control_points);
}

TEST(SplineSegment, MapsTimesToTheActiveControlPoints) {
  const SplineSegment start = splineSegmentAt(kT0, kT0, kDt, 10);
  EXPECT_EQ(start.first_control_point, 0);
  EXPECT_EQ(start.u, 0.0);
  const SplineSegment middle = splineSegmentAt(kT0 + 2.5 * kDt, kT0, kDt, 10);
  EXPECT_EQ(middle.first_control_point, 2);
  EXPECT_NEAR(middle.u, 0.5, 1e-12);
  // The end of the valid range belongs to the last segment, at u = 1.
  const SplineSegment end = splineSegmentAt(kT0 + 7 * kDt, kT0, kDt, 10);
  EXPECT_EQ(end.first_control_point, 6);
  EXPECT_NEAR(end.u, 1.0, 1e-12);
  const SE3Splined spline = constantTwistSpline(10);
  EXPECT_EQ(spline.validBegin(), kT0);
  EXPECT_NEAR(spline.validEnd(), kT0 + 0.7, 1e-15);
  EXPECT_EQ(spline.segmentAt(spline.validEnd()).first_control_point, 6);
}

TEST(SplineSegment, RejectsTimesOutsideTheValidRange) {
  try {
    splineSegmentAt(1.5, 2.0, 0.5, 5);
    FAIL() << "a time before the spline was accepted";
  } catch (const std::out_of_range& error) {
    EXPECT_EQ(std::string(error.what()),
              "splineSegmentAt: time 1.5 is outside the spline's valid range [2, 3]");
  }
  EXPECT_THROW(splineSegmentAt(3.0000001, 2.0, 0.5, 5), std::out_of_range);
  EXPECT_THROW(splineSegmentAt(2.5, 2.0, 0.5, 3), std::invalid_argument);
  EXPECT_THROW(SE3Splined(0.0, 0.0, std::vector<SE3d>(4)), std::invalid_argument);
}

TEST(SplineSegment, UniformCubicBasisIsTheTextbookOneAndSumsToOne) {
  for (const double u : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    SCOPED_TRACE("u = " + std::to_string(u));
    const std::array<double, 4> b = uniformCubicBasis(u);
    EXPECT_NEAR(b[0], std::pow(1.0 - u, 3) / 6.0, 1e-15);
    EXPECT_NEAR(b[1], (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0, 1e-15);
    EXPECT_NEAR(b[2], (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, 1e-15);
    EXPECT_NEAR(b[3], u * u * u / 6.0, 1e-15);
    EXPECT_NEAR(b[0] + b[1] + b[2] + b[3], 1.0, 1e-15);
  }
  // A straight line through translation-only control points: the pose is
  // the basis-weighted mean of the four, so the weights are the spline's own.
  std::vector<SE3d> control_points;
  for (const double x : {0.0, 1.0, 5.0, 2.0}) control_points.emplace_back(Eigen::Quaterniond::Identity(), Eigen::Vector3d(x, 0, 0));
  const SE3Splined spline(0.0, 1.0, control_points);
  const std::array<double, 4> b = uniformCubicBasis(0.3);
  EXPECT_NEAR(spline.pose(0.3).t.x(), b[1] * 1.0 + b[2] * 5.0 + b[3] * 2.0, 1e-12);
}

TEST(Se3Spline, ReproducesConstantTwistMotionExactly) {
  const SE3Splined spline = constantTwistSpline(12);
  const Vector6d xi = constantTwist();
  const Eigen::Vector3d v_B = xi.head<3>(), omega_B = xi.tail<3>();
  for (double t = spline.validBegin(); t <= spline.validEnd(); t += 0.0137) {
    const SE3d expected = startPose() * SE3d::exp(Vector6d(t * xi));
    const SE3SplineKinematics<double> k = spline.kinematics(t);
    EXPECT_LT((k.T_W_B.t - expected.t).norm(), 1e-9) << t;
    EXPECT_LT(k.T_W_B.q.angularDistance(expected.q), 1e-9) << t;
    EXPECT_LT((spline.pose(t).t - expected.t).norm(), 1e-9) << t;
    EXPECT_LT((k.linear_velocity_B - v_B).norm(), 1e-9) << t;
    EXPECT_LT((k.angular_velocity_B - omega_B).norm(), 1e-9) << t;
    const Eigen::Matrix3d R = expected.rotationMatrix();
    EXPECT_LT((k.linear_velocity_W - R * v_B).norm(), 1e-9) << t;
    EXPECT_LT((k.angular_velocity_W - R * omega_B).norm(), 1e-9) << t;
    // d/dt (R v_B) with constant v_B and omega_B: R (omega_B x v_B).
    EXPECT_LT((k.linear_acceleration_W - R * omega_B.cross(v_B)).norm(), 1e-9) << t;
    EXPECT_LT(k.angular_acceleration_B.norm(), 1e-9) << t;
  }
}

// Velocity and acceleration of a non-trivial spline against finite
// differences of its own pose, away from knots (the spline is C2 and its third
// derivative jumps there; every stencil stays inside one segment).
// Position: fourth-order stencils with h = 1e-3 (truncation ~h^4 |p^(5)|,
// rounding ~eps |p| / h^2 ~ 1e-8 for the acceleration). Rotation: the
// second-order log(R(t-h)^T R(t+h)) / 2h = omega_B + O(h^2) and a central
// difference of omega_B, with h = 1e-4 (truncation ~1e-8 |omega''|).
TEST(Se3Spline, DerivativesMatchNumericDifferentiationOfThePose) {
  const SE3Splined spline = helixSpline();
  for (int segment = 0; segment < 30; segment += 3) {
    for (double u : {0.2, 0.5, 0.77}) {
      const double t = kT0 + (segment + u) * kDt;
      const SE3SplineKinematics<double> k = spline.kinematics(t);
      const double h = 1e-3;
      const Eigen::Vector3d p_m2 = spline.pose(t - 2 * h).t, p_m1 = spline.pose(t - h).t,
                            p_0 = spline.pose(t).t, p_p1 = spline.pose(t + h).t,
                            p_p2 = spline.pose(t + 2 * h).t;
      const Eigen::Vector3d velocity = (-p_p2 + 8 * p_p1 - 8 * p_m1 + p_m2) / (12 * h);
      const Eigen::Vector3d acceleration =
          (-p_p2 + 16 * p_p1 - 30 * p_0 + 16 * p_m1 - p_m2) / (12 * h * h);
      EXPECT_LT((k.linear_velocity_W - velocity).norm(), 1e-7) << t;
      EXPECT_LT((k.linear_acceleration_W - acceleration).norm(), 1e-7) << t;
      EXPECT_LT((k.T_W_B.q.conjugate() * k.linear_velocity_W - k.linear_velocity_B).norm(), 1e-12);

      const double h_rotation = 1e-4;
      const SE3d before = spline.pose(t - h_rotation), after = spline.pose(t + h_rotation);
      const Eigen::Vector3d omega_B = logSO3(before.q.conjugate() * after.q) / (2 * h_rotation);
      EXPECT_LT((k.angular_velocity_B - omega_B).norm(), 1e-7) << t;
      const Eigen::Vector3d omega_dot_B =
          (spline.kinematics(t + h_rotation, SplineDerivatives::kVelocity).angular_velocity_B -
           spline.kinematics(t - h_rotation, SplineDerivatives::kVelocity).angular_velocity_B) /
          (2 * h_rotation);
      EXPECT_LT((k.angular_acceleration_B - omega_dot_B).norm(), 1e-7) << t;
      EXPECT_LT((k.angular_velocity_W - k.T_W_B.q * k.angular_velocity_B).norm(), 1e-12);
    }
  }
}

// The spline is a smoothed helix: with control points sampled from the helix
// it follows it to within the B-spline approximation error ~ dt^2 |p''| / 6.
TEST(Se3Spline, FollowsTheTrajectoryItWasSampledFrom) {
  const SE3Splined spline = helixSpline();
  // |p''| = 4 * 0.7^2 = 1.96 m/s^2: dt^2 |p''| / 6 = 3.3 mm.
  for (double t = spline.validBegin(); t <= spline.validEnd(); t += 0.05) {
    EXPECT_LT((spline.pose(t).t - helixPose(t).t).norm(), 3.5e-3) << t;
  }
}

Eigen::VectorXd poseAndTwist(const std::array<std::vector<double>, 4>& blocks, double u) {
  const double* pointers[4] = {blocks[0].data(), blocks[1].data(), blocks[2].data(),
                               blocks[3].data()};
  const SE3SplineKinematics<double> k =
      evaluateSe3SplineKinematics<double>(pointers, u, kDt, SplineDerivatives::kAcceleration);
  Eigen::VectorXd out(16);
  k.T_W_B.toParameters(out.data());
  out.segment<3>(7) = k.linear_velocity_W;
  out.segment<3>(10) = k.angular_velocity_B;
  out.segment<3>(13) = k.linear_acceleration_W;
  return out;
}

// Autodiff with ceres::Jet through the parameter-block form, as a cost
// functor calls it: derivatives with respect to each control point's 7
// parameters equal central differences of the double evaluation. The second
// case has two identical control points (zero relative motion: all Taylor
// branches) to check derivatives at exactly zero rotation.
TEST(Se3Spline, JetDerivativesWithRespectToControlPointsMatchNumericOnes) {
  using Jet = ceres::Jet<double, 7>;
  const SE3Splined spline = helixSpline();
  std::vector<SE3d> moving(spline.controlPoints().begin() + 5, spline.controlPoints().begin() + 9);
  std::vector<SE3d> resting = moving;
  resting[2] = resting[1];
  for (const std::vector<SE3d>& control_points : {moving, resting}) {
    std::array<std::vector<double>, 4> blocks;
    for (int i = 0; i < 4; ++i) {
      blocks[i].resize(7);
      control_points[i].toParameters(blocks[i].data());
    }
    const double u = 0.37;
    for (int varied = 0; varied < 4; ++varied) {
      std::array<std::array<Jet, 7>, 4> jet_blocks;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 7; ++j) {
          jet_blocks[i][j] = i == varied ? Jet(blocks[i][j], j) : Jet(blocks[i][j]);
        }
      }
      const Jet* pointers[4] = {jet_blocks[0].data(), jet_blocks[1].data(), jet_blocks[2].data(),
                                jet_blocks[3].data()};
      const SE3SplineKinematics<Jet> k =
          evaluateSe3SplineKinematics<Jet>(pointers, Jet(u), kDt, SplineDerivatives::kAcceleration);
      Eigen::Matrix<double, 16, 7> autodiff;
      Jet pose_block[7];
      k.T_W_B.toParameters(pose_block);
      for (int r = 0; r < 7; ++r) autodiff.row(r) = pose_block[r].v.transpose();
      for (int r = 0; r < 3; ++r) {
        autodiff.row(7 + r) = k.linear_velocity_W(r).v.transpose();
        autodiff.row(10 + r) = k.angular_velocity_B(r).v.transpose();
        autodiff.row(13 + r) = k.linear_acceleration_W(r).v.transpose();
      }
      const Eigen::MatrixXd numeric = numericJacobian(
          [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
            std::array<std::vector<double>, 4> perturbed = blocks;
            for (int j = 0; j < 7; ++j) perturbed[varied][j] = x(j);
            return poseAndTwist(perturbed, u);
          },
          Eigen::Map<const Eigen::VectorXd>(blocks[varied].data(), 7));
      EXPECT_LT((autodiff - numeric).norm(), 1e-8 * (1.0 + numeric.norm())) << varied;
      // Same values as the double evaluation.
      EXPECT_NEAR(k.T_W_B.t.x().a, poseAndTwist(blocks, u)(4), 1e-14);
    }
  }
}

// A Jet in u (e.g. through an estimated time offset) carries the time
// derivative: dp/du = dt * dp/dt.
TEST(Se3Spline, JetDerivativeWithRespectToTimeIsTheVelocity) {
  using Jet = ceres::Jet<double, 1>;
  const SE3Splined spline = helixSpline();
  const std::vector<SE3d>& cps = spline.controlPoints();
  std::array<std::array<Jet, 7>, 4> blocks;
  for (int i = 0; i < 4; ++i) {
    double raw[7];
    cps[10 + i].toParameters(raw);
    for (int j = 0; j < 7; ++j) blocks[i][j] = Jet(raw[j]);
  }
  const Jet* pointers[4] = {blocks[0].data(), blocks[1].data(), blocks[2].data(),
                            blocks[3].data()};
  const double u = 0.61;
  const SE3<Jet> pose = evaluateSe3Spline<Jet>(pointers, Jet(u, 0));
  const SE3SplineKinematics<double> k = spline.kinematics(kT0 + (10 + u) * kDt);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(pose.t(r).a, k.T_W_B.t(r), 1e-13);
    EXPECT_NEAR(pose.t(r).v(0), kDt * k.linear_velocity_W(r), 1e-12);
  }
}

}  // namespace
}  // namespace hsmap
