#include "core/geometry/so3.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "tests/core/geometry/numeric_jacobian.h"

namespace hsmap {
namespace {

using test::numericJacobian;

// Rotation vectors spanning the Taylor branch (|phi|^2 < 1e-4), its boundary
// and large angles up to nearly pi.
std::vector<Eigen::Vector3d> testRotationVectors() {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> out;
  for (double angle : {0.0, 1e-9, 1e-5, 3e-3, 9.9e-3, 1.01e-2, 0.3, 1.0, 2.5, M_PI - 1e-4}) {
    Eigen::Vector3d axis(normal(rng), normal(rng), normal(rng));
    out.push_back(axis.normalized() * angle);
  }
  return out;
}

double angleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

TEST(So3, HatIsTheCrossProductAndVeeItsInverse) {
  const Eigen::Vector3d w(0.3, -1.2, 2.0), v(-0.7, 0.4, 1.1);
  EXPECT_LT((hat(w) * v - w.cross(v)).norm(), 1e-15);
  EXPECT_LT((vee(hat(w)) - w).norm(), 1e-15);
  EXPECT_LT((hat(w) + hat(w).transpose()).norm(), 1e-15);
}

TEST(So3, ExpMatchesEigenAngleAxis) {
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    const double angle = phi.norm();
    const Eigen::Quaterniond expected =
        angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, phi / angle))
                  : Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond q = expSO3(phi);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15) << phi.transpose();
    EXPECT_LT(angleBetween(q, expected), 1e-14) << phi.transpose();
  }
}

TEST(So3, LogInvertsExpAndIgnoresTheQuaternionSign) {
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    const Eigen::Quaterniond q = expSO3(phi);
    EXPECT_LT((logSO3(q) - phi).norm(), 1e-13 * (1.0 + phi.norm())) << phi.transpose();
    const Eigen::Quaterniond minus_q(-q.w(), -q.x(), -q.y(), -q.z());
    EXPECT_LT((logSO3(minus_q) - phi).norm(), 1e-13 * (1.0 + phi.norm())) << phi.transpose();
  }
}

TEST(So3, LogAtHalfTurnGivesAnAngleOfPi) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI, axis));
  const Eigen::Vector3d phi = logSO3(q);
  EXPECT_NEAR(phi.norm(), M_PI, 1e-14);
  EXPECT_NEAR(std::abs(phi.normalized().dot(axis)), 1.0, 1e-14);
  EXPECT_LT(angleBetween(expSO3(phi), q), 1e-14);
  // Just past pi the shorter way round is about the opposite axis.
  const Eigen::Quaterniond beyond(Eigen::AngleAxisd(M_PI + 1e-3, axis));
  EXPECT_LT((logSO3(beyond) - (-(M_PI - 1e-3) * axis)).norm(), 1e-12);
}

TEST(So3, RightJacobianMatchesNumericDifferentiation) {
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    // Jr(phi) = d log(exp(phi)^-1 exp(phi + d)) / d d at d = 0.
    const Eigen::Quaterniond q = expSO3(phi);
    const Eigen::MatrixXd numeric = numericJacobian(
        [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
          return logSO3(q.conjugate() * expSO3(Eigen::Vector3d(phi + d)));
        },
        Eigen::VectorXd::Zero(3));
    EXPECT_LT((rightJacobianSO3(phi) - numeric).norm(), 1e-9) << phi.transpose();
  }
}

TEST(So3, LeftJacobianMatchesNumericDifferentiation) {
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    // Jl(phi) = d log(exp(phi + d) exp(phi)^-1) / d d at d = 0.
    const Eigen::Quaterniond q = expSO3(phi);
    const Eigen::MatrixXd numeric = numericJacobian(
        [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
          return logSO3(expSO3(Eigen::Vector3d(phi + d)) * q.conjugate());
        },
        Eigen::VectorXd::Zero(3));
    EXPECT_LT((leftJacobianSO3(phi) - numeric).norm(), 1e-9) << phi.transpose();
  }
}

TEST(So3, JacobianInversesAreInverses) {
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    EXPECT_LT((rightJacobianSO3(phi) * rightJacobianInverseSO3(phi) - Eigen::Matrix3d::Identity())
                  .norm(),
              1e-12)
        << phi.transpose();
    EXPECT_LT((leftJacobianSO3(phi) * leftJacobianInverseSO3(phi) - Eigen::Matrix3d::Identity())
                  .norm(),
              1e-12)
        << phi.transpose();
    EXPECT_LT((leftJacobianSO3(phi) - rightJacobianSO3(Eigen::Vector3d(-phi))).norm(), 1e-15);
  }
}

// Autodiff through expSO3 / logSO3 / Jr, including at exactly zero rotation
// (the Taylor branches), must equal numeric differentiation of the double code.
TEST(So3, JetDerivativesMatchNumericOnesIncludingAtZero) {
  using Jet = ceres::Jet<double, 3>;
  for (const Eigen::Vector3d& phi : testRotationVectors()) {
    Vector3<Jet> phi_jet;
    for (int i = 0; i < 3; ++i) phi_jet(i) = Jet(phi(i), i);

    const Eigen::Quaternion<Jet> q_jet = expSO3(phi_jet);
    Eigen::Matrix<double, 4, 3> exp_autodiff;
    for (int k = 0; k < 4; ++k) exp_autodiff.row(k) = q_jet.coeffs()(k).v.transpose();
    const Eigen::MatrixXd exp_numeric = numericJacobian(
        [](const Eigen::VectorXd& w) -> Eigen::VectorXd {
          return expSO3(Eigen::Vector3d(w)).coeffs();
        },
        phi);
    EXPECT_LT((exp_autodiff - exp_numeric).norm(), 1e-9) << phi.transpose();

    const Vector3<Jet> log_jet = logSO3(q_jet);  // log(exp(phi)) = phi: Jacobian I
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(log_jet(k).a, phi(k), 1e-13);
      EXPECT_LT((log_jet(k).v - Eigen::Vector3d::Unit(k)).norm(), 1e-12) << phi.transpose();
    }

    const Matrix3<Jet> jr_jet = rightJacobianSO3(phi_jet);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        const Eigen::MatrixXd numeric = numericJacobian(
            [&](const Eigen::VectorXd& w) -> Eigen::VectorXd {
              return Eigen::VectorXd::Constant(1, rightJacobianSO3(Eigen::Vector3d(w))(r, c));
            },
            phi);
        EXPECT_LT((jr_jet(r, c).v.transpose() - numeric).norm(), 1e-9) << phi.transpose();
      }
    }
  }
}

TEST(So3, JetExpAtZeroHasHalfIdentityDerivative) {
  using Jet = ceres::Jet<double, 3>;
  const Vector3<Jet> zero(Jet(0.0, 0), Jet(0.0, 1), Jet(0.0, 2));
  const Eigen::Quaternion<Jet> q = expSO3(zero);
  EXPECT_EQ(q.w().a, 1.0);
  EXPECT_EQ(q.w().v, Eigen::Vector3d::Zero());
  EXPECT_EQ(q.x().v, Eigen::Vector3d(0.5, 0.0, 0.0));
  EXPECT_EQ(q.y().v, Eigen::Vector3d(0.0, 0.5, 0.0));
  EXPECT_EQ(q.z().v, Eigen::Vector3d(0.0, 0.0, 0.5));
}

TEST(So3, InterpolationFollowsTheGeodesic) {
  const Eigen::Quaterniond q0 = expSO3(Eigen::Vector3d(0.2, -0.4, 1.0));
  const Eigen::Quaterniond q1 = expSO3(Eigen::Vector3d(-0.5, 0.3, 0.1));
  EXPECT_LT(angleBetween(interpolateSO3(q0, q1, 0.0), q0), 1e-15);
  EXPECT_LT(angleBetween(interpolateSO3(q0, q1, 1.0), q1), 1e-14);
  const double total = angleBetween(q0, q1);
  for (double s : {0.25, 0.5, 0.8}) {
    const Eigen::Quaterniond qs = interpolateSO3(q0, q1, s);
    EXPECT_NEAR(angleBetween(q0, qs), s * total, 1e-14);
    EXPECT_NEAR(angleBetween(qs, q1), (1.0 - s) * total, 1e-14);
  }
  // Same as Eigen's slerp (both take the shorter arc).
  EXPECT_LT(angleBetween(interpolateSO3(q0, q1, 0.3), q0.slerp(0.3, q1)), 1e-14);
}

TEST(So3, InsAttitudeFollowsTheNedConvention) {
  const Eigen::Vector3d forward(1, 0, 0), starboard(0, 1, 0);
  // Heading 90: the nose points east.
  EXPECT_LT((quaternionFromRollPitchHeadingDeg(0.0, 0.0, 90.0) * forward -
             Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  // Pitch +90: nose up, i.e. towards -down.
  EXPECT_LT((quaternionFromRollPitchHeadingDeg(0.0, 90.0, 0.0) * forward -
             Eigen::Vector3d(0, 0, -1)).norm(), 1e-15);
  // Roll +90: starboard wing down.
  EXPECT_LT((quaternionFromRollPitchHeadingDeg(90.0, 0.0, 0.0) * starboard -
             Eigen::Vector3d(0, 0, 1)).norm(), 1e-15);
}

TEST(So3, InsAttitudeIsZyxAndRoundTrips) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> roll_heading(-179.0, 179.0), pitch(-89.0, 89.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d rph(roll_heading(rng), pitch(rng), roll_heading(rng));
    const Eigen::Quaterniond q = quaternionFromRollPitchHeadingDeg(rph(0), rph(1), rph(2));
    const double to_rad = M_PI / 180.0;
    const Eigen::Quaterniond expected =
        Eigen::AngleAxisd(rph(2) * to_rad, Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(rph(1) * to_rad, Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(rph(0) * to_rad, Eigen::Vector3d::UnitX());
    EXPECT_LT(angleBetween(q, expected), 1e-14);
    EXPECT_LT((rollPitchHeadingDegFromQuaternion(q) - rph).norm(), 1e-10) << rph.transpose();
  }
}

// An attitude factor differentiates the conversion with Jets; both directions
// must agree with numeric differentiation.
TEST(So3, InsAttitudeConversionsDifferentiateWithJets) {
  using Jet = ceres::Jet<double, 3>;
  const Eigen::Vector3d rph(12.0, -7.5, 131.0);
  const Eigen::Quaternion<Jet> q =
      quaternionFromRollPitchHeadingDeg(Jet(rph(0), 0), Jet(rph(1), 1), Jet(rph(2), 2));
  const Eigen::MatrixXd numeric_forward = numericJacobian(
      [](const Eigen::VectorXd& a) -> Eigen::VectorXd {
        return quaternionFromRollPitchHeadingDeg(a(0), a(1), a(2)).coeffs();
      },
      rph);
  for (int k = 0; k < 4; ++k) {
    EXPECT_LT((q.coeffs()(k).v.transpose() - numeric_forward.row(k)).norm(), 1e-10);
  }
  // Back to angles: the composition is the identity, so its Jacobian is I.
  const Vector3<Jet> back = rollPitchHeadingDegFromQuaternion(q);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(back(k).a, rph(k), 1e-12);
    EXPECT_LT((back(k).v - Eigen::Vector3d::Unit(k)).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace hsmap
