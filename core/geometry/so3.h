#pragma once
// SO(3) helpers on unit quaternions (Hamilton, Eigen's convention).
//
// A rotation vector omega (axis * angle, radians) maps to the unit quaternion
//     exp(omega) = [cos(theta/2), sin(theta/2) * omega / theta],  theta = |omega|,
// and log is its inverse on angles in [0, pi] (q and -q are the same rotation;
// log picks the representative with w >= 0).
//
// Jacobians (Barfoot, "State Estimation for Robotics", sec. 7.1.5), with
// Phi = hat(phi):
//   right:  exp(phi + d) ~= exp(phi) * exp(Jr(phi) d)
//           Jr = I - a Phi + b Phi^2
//   left:   exp(phi + d) ~= exp(Jl(phi) d) * exp(phi),   Jl(phi) = Jr(-phi)
//           Jl = I + a Phi + b Phi^2
//   inverses: Jr^-1 = I + Phi/2 + e Phi^2,  Jl^-1 = I - Phi/2 + e Phi^2
//   a = (1 - cos theta) / theta^2,  b = (theta - sin theta) / theta^3,
//   e = 1/theta^2 - cot(theta/2) / (2 theta).
//
// Everything is templated on the scalar so that Ceres' autodiff Jets go
// through. Near theta = 0 the closed forms divide by powers of theta; there we
// switch to their Taylor series in theta^2 = |omega|^2, a polynomial in the
// components, so values are accurate and Jet derivatives exact (no sqrt of an
// exact zero is ever taken).
//
// Attitude: an INS reports roll, pitch, heading in degrees, ZYX, body to NED:
//   R_W_B = Rz(heading) * Ry(pitch) * Rx(roll).
// The inverse conversion returns roll, heading in (-180, 180] and pitch in
// [-90, 90]; at pitch = +-90 (gimbal lock) roll and heading are not separable
// and the split returned is arbitrary.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "core/geometry/matrix_types.h"

namespace hsmap {

namespace so3_detail {

// Below this theta^2 the Jacobian coefficients use their Taylor series (error
// of the truncated series < 1e-17 there; the closed forms lose digits to
// cancellation below it).
inline constexpr double kSmallAngleSquared = 1e-4;
// Below this |vec(q)|^2 logSO3 uses its series (truncation error < 1e-18).
inline constexpr double kSmallSineSquared = 1e-6;

inline constexpr double kDegToRad = 0.017453292519943295769;
inline constexpr double kRadToDeg = 57.295779513082320877;

// a = (1 - cos theta) / theta^2 and b = (theta - sin theta) / theta^3.
template <class T>
void jacobianCoefficients(const T& theta2, T* a, T* b) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (theta2 < T(kSmallAngleSquared)) {
    *a = T(0.5) - theta2 / 24.0 + theta2 * theta2 / 720.0;
    *b = T(1.0 / 6.0) - theta2 / 120.0 + theta2 * theta2 / 5040.0;
  } else {
    const T theta = sqrt(theta2);
    // 1 - cos(theta) = 2 sin^2(theta/2), without the cancellation of the former.
    const T half_sine = sin(theta / 2.0);
    *a = T(2) * half_sine * half_sine / theta2;
    *b = (theta - sin(theta)) / (theta2 * theta);
  }
}

// e = 1/theta^2 - cot(theta/2) / (2 theta); finite up to theta -> 2 pi.
template <class T>
T inverseJacobianCoefficient(const T& theta2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (theta2 < T(kSmallAngleSquared)) {
    return T(1.0 / 12.0) + theta2 / 720.0 + theta2 * theta2 / 30240.0;
  }
  const T theta = sqrt(theta2);
  const T half = theta / 2.0;
  return T(1) / theta2 - cos(half) / (T(2) * theta * sin(half));
}

}  // namespace so3_detail

// hat(w) * v = w x v.
template <class Derived>
Matrix3<typename Derived::Scalar> hat(const Eigen::MatrixBase<Derived>& w) {
  using T = typename Derived::Scalar;
  Matrix3<T> W;
  W << T(0), -w(2), w(1),
       w(2), T(0), -w(0),
       -w(1), w(0), T(0);
  return W;
}

// Inverse of hat. Averages the upper and lower triangles, so a matrix that is
// only nearly skew-symmetric (rounding) gives the vector of its skew part.
template <class Derived>
Vector3<typename Derived::Scalar> vee(const Eigen::MatrixBase<Derived>& W) {
  using T = typename Derived::Scalar;
  return Vector3<T>((W(2, 1) - W(1, 2)) / 2.0, (W(0, 2) - W(2, 0)) / 2.0,
                    (W(1, 0) - W(0, 1)) / 2.0);
}

// Unit quaternion of the rotation vector omega (radians).
template <class Derived>
Eigen::Quaternion<typename Derived::Scalar> expSO3(const Eigen::MatrixBase<Derived>& omega) {
  using T = typename Derived::Scalar;
  using std::cos;
  using std::sin;
  using std::sqrt;
  const T theta2 = omega.squaredNorm();
  T real;
  T imag_factor;  // sin(theta/2) / theta
  if (theta2 < T(so3_detail::kSmallAngleSquared)) {
    real = T(1) - theta2 / 8.0 + theta2 * theta2 / 384.0;
    imag_factor = T(0.5) - theta2 / 48.0 + theta2 * theta2 / 3840.0;
  } else {
    const T theta = sqrt(theta2);
    real = cos(theta / 2.0);
    imag_factor = sin(theta / 2.0) / theta;
  }
  return Eigen::Quaternion<T>(real, imag_factor * omega(0), imag_factor * omega(1),
                              imag_factor * omega(2));
}

// Rotation vector of q with angle in [0, pi]; q and -q give the same result
// (except exactly at pi, where both +-pi*axis are valid).
template <class Derived>
Vector3<typename Derived::Scalar> logSO3(const Eigen::QuaternionBase<Derived>& q) {
  using T = typename Derived::Scalar;
  using std::atan2;
  using std::sqrt;
  T w = q.w();
  Vector3<T> v = q.vec();
  if (w < T(0)) {
    w = -w;
    v = -v;
  }
  const T n2 = v.squaredNorm();
  T factor;  // theta / |v|, with theta = 2 atan2(|v|, w)
  if (n2 < T(so3_detail::kSmallSineSquared)) {
    // 2 atan(n / w) / n = (2 / w) (1 - x/3 + x^2/5 - ...),  x = n^2 / w^2.
    const T x = n2 / (w * w);
    factor = (T(2) / w) * (T(1) - x / 3.0 + x * x / 5.0);
  } else {
    const T n = sqrt(n2);
    factor = T(2) * atan2(n, w) / n;
  }
  return factor * v;
}

template <class Derived>
Matrix3<typename Derived::Scalar> rightJacobianSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  T a, b;
  so3_detail::jacobianCoefficients(T(phi.squaredNorm()), &a, &b);
  const Matrix3<T> Phi = hat(phi);
  return Matrix3<T>::Identity() - a * Phi + b * Phi * Phi;
}

template <class Derived>
Matrix3<typename Derived::Scalar> leftJacobianSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  T a, b;
  so3_detail::jacobianCoefficients(T(phi.squaredNorm()), &a, &b);
  const Matrix3<T> Phi = hat(phi);
  return Matrix3<T>::Identity() + a * Phi + b * Phi * Phi;
}

template <class Derived>
Matrix3<typename Derived::Scalar> rightJacobianInverseSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const T e = so3_detail::inverseJacobianCoefficient(T(phi.squaredNorm()));
  const Matrix3<T> Phi = hat(phi);
  return Matrix3<T>::Identity() + Phi / 2.0 + e * Phi * Phi;
}

template <class Derived>
Matrix3<typename Derived::Scalar> leftJacobianInverseSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const T e = so3_detail::inverseJacobianCoefficient(T(phi.squaredNorm()));
  const Matrix3<T> Phi = hat(phi);
  return Matrix3<T>::Identity() - Phi / 2.0 + e * Phi * Phi;
}

// Geodesic interpolation q0 * exp(s * log(q0^-1 q1)): s = 0 gives q0, s = 1
// gives q1 (up to sign), constant angular rate in between along the shorter arc.
template <class T>
Eigen::Quaternion<T> interpolateSO3(const Eigen::Quaternion<T>& q0, const Eigen::Quaternion<T>& q1,
                                    const T& s) {
  const Vector3<T> delta = logSO3(q0.conjugate() * q1);
  return q0 * expSO3(Vector3<T>(s * delta));
}

// q_W_B from INS attitude (degrees): Rz(heading) * Ry(pitch) * Rx(roll).
template <class T>
Eigen::Quaternion<T> quaternionFromRollPitchHeadingDeg(const T& roll_deg, const T& pitch_deg,
                                                       const T& heading_deg) {
  using std::cos;
  using std::sin;
  const T half_roll = roll_deg * (so3_detail::kDegToRad / 2.0);
  const T half_pitch = pitch_deg * (so3_detail::kDegToRad / 2.0);
  const T half_heading = heading_deg * (so3_detail::kDegToRad / 2.0);
  const Eigen::Quaternion<T> q_roll(cos(half_roll), sin(half_roll), T(0), T(0));
  const Eigen::Quaternion<T> q_pitch(cos(half_pitch), T(0), sin(half_pitch), T(0));
  const Eigen::Quaternion<T> q_heading(cos(half_heading), T(0), T(0), sin(half_heading));
  return q_heading * q_pitch * q_roll;
}

// (roll, pitch, heading) in degrees of q_W_B; see the header comment for ranges.
template <class T>
Vector3<T> rollPitchHeadingDegFromQuaternion(const Eigen::Quaternion<T>& q_W_B) {
  using std::asin;
  using std::atan2;
  const Matrix3<T> R = q_W_B.toRotationMatrix();
  T minus_sin_pitch = R(2, 0);
  // Rounding can push |R(2,0)| a hair above 1, where asin is undefined.
  if (minus_sin_pitch > T(1)) minus_sin_pitch = T(1);
  if (minus_sin_pitch < T(-1)) minus_sin_pitch = T(-1);
  const T roll = atan2(R(2, 1), R(2, 2));
  const T pitch = -asin(minus_sin_pitch);
  const T heading = atan2(R(1, 0), R(0, 0));
  return Vector3<T>(roll * so3_detail::kRadToDeg, pitch * so3_detail::kRadToDeg,
                    heading * so3_detail::kRadToDeg);
}

}  // namespace hsmap
