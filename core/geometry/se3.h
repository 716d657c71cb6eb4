#pragma once
// SE3<T>: a rigid transform T_A_B = (q, t) with p_A = T_A_B * p_B = q * p_B + t.
//
// Tangent vectors are 6-vectors xi = [rho; phi], TRANSLATION FIRST, rotation
// second (Barfoot's ordering), with hat(xi) = [hat(phi) rho; 0 0]:
//   exp(xi) = (expSO3(phi), Jl(phi) rho),   log(T) = [Jl(phi)^-1 t; logSO3(q)].
// Perturbations are on the RIGHT (in the frame B being mapped from):
//   T (+) delta = T * exp(delta).
// With that convention:
//   d(T exp(delta) p)/d delta |0 = [R, -R hat(p)]        (3x6)
//   d(T p)/d p                   = R                     (3x3)
//   exp(xi + d) ~= exp(xi) exp(Jr(xi) d)                 (right Jacobian)
//   exp(xi + d) ~= exp(Jl(xi) d) exp(xi)                 (left Jacobian)
//   log(T exp(delta)) ~= log(T) + Jr(log T)^-1 delta     (derivative of log)
//   T exp(xi) T^-1 = exp(Ad(T) xi),  Ad(T) = [R, hat(t) R; 0, R]
// and the SE(3) Jacobians are (Barfoot, "State Estimation for Robotics",
// eq. 7.83-7.86) Jl(xi) = [Jl(phi), Q(rho, phi); 0, Jl(phi)], Jr(xi) = Jl(-xi),
// with Q the closed form of Barfoot eq. 7.86 (Taylor series near phi = 0).
//
// Ceres parameter block: 7 scalars [qx qy qz qw tx ty tz], Eigen's quaternion
// memory order followed by the translation, so that
// Eigen::Map<const Eigen::Quaternion<T>>(block) reads the rotation in place and
// ceres::ProductManifold<ceres::EigenQuaternionManifold,
// ceres::EuclideanManifold<3>> is the matching manifold. The same layout is
// used by core/graph's Values for pose3 variables. fromParameters() does not
// renormalise the quaternion: the manifold keeps it unit.
//
// Templated on the scalar for Ceres autodiff; all small-angle branches use
// Taylor series (see so3.h).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/geometry/matrix_types.h"
#include "core/geometry/so3.h"

namespace hsmap {

namespace se3_detail {

// Q(rho, phi) of the left Jacobian of SE(3) (Barfoot eq. 7.86).
template <class T>
Matrix3<T> leftJacobianQ(const Vector3<T>& rho, const Vector3<T>& phi) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta2 = phi.squaredNorm();
  T b, c, d;
  if (theta2 < T(so3_detail::kSmallAngleSquared)) {
    const T theta4 = theta2 * theta2;
    b = T(1.0 / 6.0) - theta2 / 120.0 + theta4 / 5040.0;
    c = T(1.0 / 24.0) - theta2 / 720.0 + theta4 / 40320.0;
    d = T(1.0 / 120.0) - theta2 / 2520.0 + theta4 / 120960.0;
  } else {
    const T theta = sqrt(theta2);
    const T s = sin(theta);
    const T co = cos(theta);
    // 2 cos(theta) - 2 = -4 sin^2(theta/2): one cancellation fewer in c.
    const T half_sine = sin(theta / 2.0);
    b = (theta - s) / (theta2 * theta);
    c = (theta2 - T(4) * half_sine * half_sine) / (T(2) * theta2 * theta2);
    d = (T(2) * theta - T(3) * s + theta * co) / (T(2) * theta2 * theta2 * theta);
  }
  const Matrix3<T> P = hat(phi);
  const Matrix3<T> Rh = hat(rho);
  const Matrix3<T> PR = P * Rh;
  const Matrix3<T> RP = Rh * P;
  const Matrix3<T> PRP = PR * P;
  return Rh / 2.0 + b * (PR + RP + PRP) + c * (P * PR + RP * P - T(3) * PRP) +
         d * (PRP * P + P * PRP);
}

}  // namespace se3_detail

template <class T>
class SE3 {
 public:
  using Scalar = T;
  static constexpr int kNumParameters = 7;  // [qx qy qz qw tx ty tz]
  static constexpr int kTangentSize = 6;    // [rho; phi]

  // Rotation R_A_B as a unit quaternion and translation t_A_B (the origin of
  // B expressed in A). Public: SE3 is a plain value.
  Eigen::Quaternion<T> q;
  Vector3<T> t;

  SE3() : q(Eigen::Quaternion<T>::Identity()), t(Vector3<T>::Zero()) {}
  SE3(const Eigen::Quaternion<T>& rotation, const Vector3<T>& translation)
      : q(rotation), t(translation) {}

  static SE3 identity() { return SE3(); }

  // From a 7-scalar block [qx qy qz qw tx ty tz] (see the header comment).
  static SE3 fromParameters(const T* parameters) {
    return SE3(Eigen::Quaternion<T>(parameters[3], parameters[0], parameters[1], parameters[2]),
               Vector3<T>(parameters[4], parameters[5], parameters[6]));
  }
  void toParameters(T* parameters) const {
    parameters[0] = q.x();
    parameters[1] = q.y();
    parameters[2] = q.z();
    parameters[3] = q.w();
    parameters[4] = t.x();
    parameters[5] = t.y();
    parameters[6] = t.z();
  }

  // From a homogeneous matrix whose top-left block is a rotation.
  static SE3 fromMatrix(const Matrix4<T>& m) {
    return SE3(Eigen::Quaternion<T>(Matrix3<T>(m.template topLeftCorner<3, 3>())).normalized(),
               Vector3<T>(m.template topRightCorner<3, 1>()));
  }

  Matrix3<T> rotationMatrix() const { return q.toRotationMatrix(); }
  Matrix4<T> matrix() const {
    Matrix4<T> m = Matrix4<T>::Identity();
    m.template topLeftCorner<3, 3>() = rotationMatrix();
    m.template topRightCorner<3, 1>() = t;
    return m;
  }

  // T_A_C = T_A_B * T_B_C.
  SE3 operator*(const SE3& other) const { return SE3(q * other.q, q * other.t + t); }
  // p_A = T_A_B * p_B.
  Vector3<T> operator*(const Vector3<T>& p) const { return q * p + t; }

  SE3 inverse() const {
    const Eigen::Quaternion<T> q_inv = q.conjugate();
    return SE3(q_inv, -(q_inv * t));
  }

  // Jl(phi) rho and Jl(phi)^-1 t are applied through cross products rather
  // than 3x3 matrices: both run inside every spline evaluation, where with
  // autodiff Jets each scalar operation costs dozens of flops.
  static SE3 exp(const Vector6<T>& xi) {
    const Vector3<T> rho = xi.template head<3>();
    const Vector3<T> phi = xi.template tail<3>();
    T a, b;
    so3_detail::jacobianCoefficients(T(phi.squaredNorm()), &a, &b);
    const Vector3<T> phi_x_rho = phi.cross(rho);
    return SE3(expSO3(phi), Vector3<T>(rho + a * phi_x_rho + b * phi.cross(phi_x_rho)));
  }

  Vector6<T> log() const {
    const Vector3<T> phi = logSO3(q);
    const T e = so3_detail::inverseJacobianCoefficient(T(phi.squaredNorm()));
    const Vector3<T> phi_x_t = phi.cross(t);
    Vector6<T> xi;
    xi.template head<3>() = t - phi_x_t / 2.0 + e * phi.cross(phi_x_t);
    xi.template tail<3>() = phi;
    return xi;
  }

  // Ad(T) = [R, hat(t) R; 0, R] for xi = [rho; phi].
  Matrix6<T> adjoint() const {
    const Matrix3<T> R = rotationMatrix();
    Matrix6<T> ad;
    ad.template topLeftCorner<3, 3>() = R;
    ad.template topRightCorner<3, 3>() = hat(t) * R;
    ad.template bottomLeftCorner<3, 3>().setZero();
    ad.template bottomRightCorner<3, 3>() = R;
    return ad;
  }
  // Ad(T) * xi without forming the 6x6 matrix.
  Vector6<T> adjointTimes(const Vector6<T>& xi) const {
    const Vector3<T> R_phi = q * Vector3<T>(xi.template tail<3>());
    Vector6<T> out;
    out.template head<3>() = q * Vector3<T>(xi.template head<3>()) + t.cross(R_phi);
    out.template tail<3>() = R_phi;
    return out;
  }

  // Converts the scalar type (double -> Jet, float <-> double).
  template <class U>
  SE3<U> cast() const {
    return SE3<U>(q.template cast<U>(), t.template cast<U>());
  }

  // a * exp(s * log(a^-1 b)): a at s = 0, b at s = 1, constant body twist.
  static SE3 interpolate(const SE3& a, const SE3& b, const T& s) {
    const Vector6<T> xi = (a.inverse() * b).log();
    return a * exp(Vector6<T>(s * xi));
  }

  // d(T exp(delta) p_B)/d delta at delta = 0: [R, -R hat(p_B)] (3x6).
  Eigen::Matrix<T, 3, 6> jacobianOfActionWrtPose(const Vector3<T>& p_B) const {
    const Matrix3<T> R = rotationMatrix();
    Eigen::Matrix<T, 3, 6> J;
    J.template leftCols<3>() = R;
    J.template rightCols<3>() = -R * hat(p_B);
    return J;
  }
  // d(T p_B)/d p_B = R.
  Matrix3<T> jacobianOfActionWrtPoint() const { return rotationMatrix(); }

  static Matrix6<T> leftJacobian(const Vector6<T>& xi) {
    const Vector3<T> rho = xi.template head<3>();
    const Vector3<T> phi = xi.template tail<3>();
    const Matrix3<T> J = leftJacobianSO3(phi);
    Matrix6<T> out;
    out.template topLeftCorner<3, 3>() = J;
    out.template topRightCorner<3, 3>() = se3_detail::leftJacobianQ(rho, phi);
    out.template bottomLeftCorner<3, 3>().setZero();
    out.template bottomRightCorner<3, 3>() = J;
    return out;
  }
  static Matrix6<T> leftJacobianInverse(const Vector6<T>& xi) {
    const Vector3<T> rho = xi.template head<3>();
    const Vector3<T> phi = xi.template tail<3>();
    const Matrix3<T> J_inv = leftJacobianInverseSO3(phi);
    Matrix6<T> out;
    out.template topLeftCorner<3, 3>() = J_inv;
    out.template topRightCorner<3, 3>() = -J_inv * se3_detail::leftJacobianQ(rho, phi) * J_inv;
    out.template bottomLeftCorner<3, 3>().setZero();
    out.template bottomRightCorner<3, 3>() = J_inv;
    return out;
  }
  static Matrix6<T> rightJacobian(const Vector6<T>& xi) { return leftJacobian(Vector6<T>(-xi)); }
  static Matrix6<T> rightJacobianInverse(const Vector6<T>& xi) {
    return leftJacobianInverse(Vector6<T>(-xi));
  }
};

using SE3d = SE3<double>;

// The Lie bracket of se(3), [a, b] = vee(hat(a) hat(b) - hat(b) hat(a)) = ad(a) b:
// [phi_a x rho_b + rho_a x phi_b; phi_a x phi_b] for [rho; phi] vectors.
template <class T>
Vector6<T> lieBracketSE3(const Vector6<T>& a, const Vector6<T>& b) {
  const Vector3<T> rho_a = a.template head<3>();
  const Vector3<T> phi_a = a.template tail<3>();
  const Vector3<T> rho_b = b.template head<3>();
  const Vector3<T> phi_b = b.template tail<3>();
  Vector6<T> out;
  out.template head<3>() = phi_a.cross(rho_b) + rho_a.cross(phi_b);
  out.template tail<3>() = phi_a.cross(phi_b);
  return out;
}

}  // namespace hsmap
