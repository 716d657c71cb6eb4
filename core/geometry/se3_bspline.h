#pragma once
// Uniform cumulative cubic B-spline on SE(3) (Lovegrove, Patron-Perez, Sibley,
// "Spline Fusion", BMVC 2013; derivatives as in Sommer et al., CVPR 2020).
//
// Time convention. Control points T_0 .. T_{N-1} (N >= 4), knot spacing dt,
// start time t0. For a time t, with s = (t - t0) / dt:
//   i = floor(s) (the first active control point), u = s - i in [0, 1),
// and the four active control points are T_i, T_{i+1}, T_{i+2}, T_{i+3}.
// The valid time range is [t0, t0 + (N - 3) dt]; at its end i = N - 4, u = 1.
// (Near time t0 + k dt the pose is close to control point k + 1: it is the
// weighted average (1/6, 4/6, 1/6) of control points k, k+1, k+2.)
//
// Pose. With Omega_j = log(T_{i+j-1}^-1 T_{i+j}) (SE(3) log, [rho; phi]) and
// the cumulative cubic basis
//   Bt(u) = C [1, u, u^2, u^3]^T,   C = 1/6 [6 0 0 0; 5 3 -3 1; 1 3 3 -2; 0 0 0 1],
//   T(u) = T_i * A_1 * A_2 * A_3,   A_j = exp(Bt_j(u) Omega_j).
// Bt_0 = 1 always; Bt_j(0) = (1, 5/6, 1/6, 0) and Bt_j(1) = (1, 1, 5/6, 1/6).
//
// Velocity. Let xi_j be the body twist of the partial product
// P_j = T_i A_1 ... A_j (P_j^-1 dP_j/dt = hat(xi_j)). Since
// A_j^-1 dA_j/dt = hat(w_j) with w_j = dBt_j/dt Omega_j (A_j commutes with
// hat(Omega_j)), and (P A)^-1 d(P A) = A^-1 (P^-1 dP) A + A^-1 dA:
//   xi_0 = 0,   xi_j = Ad(A_j^-1) xi_{j-1} + w_j.
// Acceleration. d/dt (A^-1 X A) = A^-1 X dA - A^-1 dA A^-1 X A = [Y, w]
// with Y = Ad(A^-1) X, the se(3) Lie bracket (lieBracketSE3), so
//   dxi_j/dt = Ad(A_j^-1) dxi_{j-1}/dt + [Ad(A_j^-1) xi_{j-1}, w_j]
//              + d2Bt_j/dt2 Omega_j.
// The body twist xi_3 = [v_B; omega_B] gives, with T(t) = T_W_B = (R, p):
//   dR/dt = R hat(omega_B), dp/dt = R v_B,
//   d2p/dt2 = R (omega_B x v_B + dv_B/dt), domega_W/dt = R domega_B/dt.
//
// Ceres form. evaluateSe3Spline*() take four parameter blocks in SE3's layout
// [qx qy qz qw tx ty tz] (see se3.h) and a templated u, so a cost functor can
// differentiate with respect to the control points and, through u, the time
// (e.g. the UHI time offset). The functor chooses the segment i from the
// current estimate; u slightly outside [0, 1] stays a smooth polynomial
// extension of that segment.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/matrix_types.h"
#include "core/geometry/se3.h"

namespace hsmap {

// What a time maps to: the first of the four active control points and the
// normalised time u in [0, 1] within its segment.
struct SplineSegment {
  int first_control_point = 0;
  double u = 0.0;
};

// Segment of time t for N control points, knot spacing dt, start t0. Throws
// std::out_of_range outside [t0, t0 + (N - 3) dt] and std::invalid_argument
// for N < 4 or dt <= 0.
SplineSegment splineSegmentAt(double t, double t0, double dt, int num_control_points);

// Pose and its time derivatives at one time; B is the moving frame, W the
// frame the control points are expressed in (T_W_B).
template <class T>
struct SE3SplineKinematics {
  SE3<T> T_W_B;
  Vector3<T> linear_velocity_B;      // v_B = R^T dp/dt
  Vector3<T> angular_velocity_B;     // omega_B: dR/dt = R hat(omega_B)
  Vector3<T> linear_velocity_W;      // dp/dt
  Vector3<T> angular_velocity_W;     // R omega_B
  // Filled only when acceleration was requested (zero otherwise).
  Vector3<T> linear_acceleration_W;  // d2p/dt2
  Vector3<T> angular_acceleration_B; // d omega_B / dt
};

namespace spline_detail {

// Cumulative basis Bt_j(u), j = 0..3, and its first and second derivatives
// with respect to u.
template <class T>
void cumulativeBasis(const T& u, std::array<T, 4>* b, std::array<T, 4>* db, std::array<T, 4>* d2b) {
  const T u2 = u * u;
  const T u3 = u2 * u;
  (*b)[0] = T(1);
  (*b)[1] = (T(5) + T(3) * u - T(3) * u2 + u3) / 6.0;
  (*b)[2] = (T(1) + T(3) * u + T(3) * u2 - T(2) * u3) / 6.0;
  (*b)[3] = u3 / 6.0;
  if (db != nullptr) {
    (*db)[0] = T(0);
    (*db)[1] = (T(3) - T(6) * u + T(3) * u2) / 6.0;
    (*db)[2] = (T(3) + T(6) * u - T(6) * u2) / 6.0;
    (*db)[3] = u2 / 2.0;
  }
  if (d2b != nullptr) {
    (*d2b)[0] = T(0);
    (*d2b)[1] = (T(-6) + T(6) * u) / 6.0;
    (*d2b)[2] = (T(6) - T(12) * u) / 6.0;
    (*d2b)[3] = u;
  }
}

}  // namespace spline_detail

// The uniform cubic B-spline basis B_j(u), j = 0..3: how much each of a
// segment's four control points weighs in the pose at normalised time u
// (B_j = Bt_j - Bt_{j+1} of the cumulative basis; they sum to 1). The last,
// u^3 / 6, is why a control point barely moves the start of its segment.
inline std::array<double, 4> uniformCubicBasis(double u) {
  std::array<double, 4> cumulative;
  spline_detail::cumulativeBasis<double>(u, &cumulative, nullptr, nullptr);
  return {cumulative[0] - cumulative[1], cumulative[1] - cumulative[2], cumulative[2] - cumulative[3],
          cumulative[3]};
}

enum class SplineDerivatives { kVelocity, kAcceleration };

// Kinematics from the four active control points (T_i .. T_{i+3}) at
// normalised time u of a spline with knot spacing dt.
template <class T>
SE3SplineKinematics<T> evaluateSe3SplineKinematics(const std::array<SE3<T>, 4>& control_points,
                                                   const T& u, double dt,
                                                   SplineDerivatives order) {
  const bool with_acceleration = order == SplineDerivatives::kAcceleration;
  std::array<T, 4> b, db, d2b;
  spline_detail::cumulativeBasis(u, &b, &db, &d2b);
  const double inv_dt = 1.0 / dt;
  const double inv_dt2 = inv_dt * inv_dt;

  SE3<T> pose = control_points[0];
  Vector6<T> twist = Vector6<T>::Zero();
  Vector6<T> twist_rate = Vector6<T>::Zero();
  for (int j = 1; j <= 3; ++j) {
    const Vector6<T> omega = (control_points[j - 1].inverse() * control_points[j]).log();
    const SE3<T> A = SE3<T>::exp(Vector6<T>(b[j] * omega));
    const SE3<T> A_inv = A.inverse();
    const Vector6<T> w = (db[j] * inv_dt) * omega;
    const Vector6<T> carried = A_inv.adjointTimes(twist);
    if (with_acceleration) {
      twist_rate = A_inv.adjointTimes(twist_rate) + lieBracketSE3(carried, w) +
                   (d2b[j] * inv_dt2) * omega;
    }
    twist = carried + w;
    pose = pose * A;
  }

  SE3SplineKinematics<T> out;
  out.T_W_B = pose;
  out.linear_velocity_B = twist.template head<3>();
  out.angular_velocity_B = twist.template tail<3>();
  out.linear_velocity_W = pose.q * out.linear_velocity_B;
  out.angular_velocity_W = pose.q * out.angular_velocity_B;
  if (with_acceleration) {
    const Vector3<T> v_dot_B = twist_rate.template head<3>();
    out.linear_acceleration_W =
        pose.q * Vector3<T>(out.angular_velocity_B.cross(out.linear_velocity_B) + v_dot_B);
    out.angular_acceleration_B = twist_rate.template tail<3>();
  } else {
    out.linear_acceleration_W.setZero();
    out.angular_acceleration_B.setZero();
  }
  return out;
}

// Pose only (cheaper: no adjoints).
template <class T>
SE3<T> evaluateSe3SplinePose(const std::array<SE3<T>, 4>& control_points, const T& u) {
  std::array<T, 4> b;
  spline_detail::cumulativeBasis<T>(u, &b, nullptr, nullptr);
  SE3<T> pose = control_points[0];
  for (int j = 1; j <= 3; ++j) {
    const Vector6<T> omega = (control_points[j - 1].inverse() * control_points[j]).log();
    pose = pose * SE3<T>::exp(Vector6<T>(b[j] * omega));
  }
  return pose;
}

// Ceres forms: blocks[k] points to the 7-scalar block of control point i + k.
template <class T>
SE3<T> evaluateSe3Spline(const T* const* blocks, const T& u) {
  return evaluateSe3SplinePose<T>({SE3<T>::fromParameters(blocks[0]),
                                   SE3<T>::fromParameters(blocks[1]),
                                   SE3<T>::fromParameters(blocks[2]),
                                   SE3<T>::fromParameters(blocks[3])},
                                  u);
}

template <class T>
SE3SplineKinematics<T> evaluateSe3SplineKinematics(const T* const* blocks, const T& u, double dt,
                                                   SplineDerivatives order) {
  return evaluateSe3SplineKinematics<T>({SE3<T>::fromParameters(blocks[0]),
                                         SE3<T>::fromParameters(blocks[1]),
                                         SE3<T>::fromParameters(blocks[2]),
                                         SE3<T>::fromParameters(blocks[3])},
                                        u, dt, order);
}

// A whole spline: control points with their time grid.
template <class T>
class SE3Spline {
 public:
  // Throws std::invalid_argument for fewer than 4 control points or a
  // non-positive / non-finite dt or non-finite t0.
  SE3Spline(double t0, double dt, std::vector<SE3<T>> control_points)
      : t0_(t0), dt_(dt), control_points_(std::move(control_points)) {
    if (!std::isfinite(t0)) throw std::invalid_argument("SE3Spline: t0 must be finite");
    if (!(std::isfinite(dt) && dt > 0.0)) {
      throw std::invalid_argument("SE3Spline: dt must be a positive finite number, got " +
                                  std::to_string(dt));
    }
    if (control_points_.size() < 4) {
      throw std::invalid_argument("SE3Spline: a cubic spline needs at least 4 control points, got " +
                                  std::to_string(control_points_.size()));
    }
  }

  double t0() const { return t0_; }
  double dt() const { return dt_; }
  int numControlPoints() const { return static_cast<int>(control_points_.size()); }
  // Valid time range [validBegin(), validEnd()].
  double validBegin() const { return t0_; }
  double validEnd() const { return t0_ + (numControlPoints() - 3) * dt_; }

  const std::vector<SE3<T>>& controlPoints() const { return control_points_; }
  std::vector<SE3<T>>& controlPoints() { return control_points_; }

  // Throws std::out_of_range outside the valid time range.
  SplineSegment segmentAt(double t) const {
    return splineSegmentAt(t, t0_, dt_, numControlPoints());
  }

  SE3<T> pose(double t) const {
    const SplineSegment segment = segmentAt(t);
    return evaluateSe3SplinePose<T>(active(segment.first_control_point), T(segment.u));
  }

  SE3SplineKinematics<T> kinematics(double t,
                                    SplineDerivatives order = SplineDerivatives::kAcceleration) const {
    const SplineSegment segment = segmentAt(t);
    return evaluateSe3SplineKinematics<T>(active(segment.first_control_point), T(segment.u), dt_,
                                          order);
  }

 private:
  std::array<SE3<T>, 4> active(int first) const {
    return {control_points_[first], control_points_[first + 1], control_points_[first + 2],
            control_points_[first + 3]};
  }

  double t0_;
  double dt_;
  std::vector<SE3<T>> control_points_;
};

using SE3Splined = SE3Spline<double>;

}  // namespace hsmap
