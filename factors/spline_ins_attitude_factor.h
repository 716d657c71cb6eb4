#pragma once
// SplineInsAttitudeFactor: the INS attitude of the body B at its own time
// t_fix, constraining the rotation of the trajectory spline through the known
// mounting rotation q_B_C (InsAttitudeFactor's model with the pose taken from
// the spline).
//
//   variables  S(i), S(i+1), S(i+2), S(i+3): the four control points (poses
//              T_W_C, [qx qy qz qw tx ty tz]) active at t_fix
//   model      T_W_C(t_fix) = spline(S(i..i+3), u) (core/geometry/se3_bspline.h),
//              i, u from SplineTiming::segmentAt(t_fix), fixed at construction;
//              q_W_B = q_W_C(t_fix) * q_B_C^-1
//   residual   r = log(q_W_B_measured^-1 * q_W_C(t_fix) * q_B_C^-1)  (3, radians)
// r is the rotation vector of the error expressed in B (right perturbation:
// q_W_B = q_W_B_measured * exp(r)): about the body's x (~roll), y (~pitch)
// and z (~heading) axes for small pitch and roll, so a noise model from the
// survey's sigma_attitude_deg = [roll, pitch, heading] is
// fromSigmas(those * pi/180). The measured attitude must be q_W_B (body to
// NED), e.g. from quaternionFromRollPitchHeadingDeg() in core/geometry/so3.h.
//
// Why at the fix's own time: the heading changes while the vehicle turns, so
// an attitude attached to the wrong time is a systematic error; on the spline
// the fix constrains the pose at exactly the time it was measured (as for
// positions, where a 20 ms mismatch at 0.4 m/s is already 8 mm).
//
// Jacobians: Ceres autodiff of SplineInsAttitudeResidual.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/geometry/so3.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/spline_timing.h"

namespace hsmap {

// Ceres functor: (control points S(i..i+3) [7 each]) -> residual [3].
struct SplineInsAttitudeResidual {
  double u;                           // normalised time of the fix in segment i
  Eigen::Quaterniond q_B_W_measured;  // q_W_B_measured^-1
  Eigen::Quaterniond q_C_B;           // q_B_C^-1

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, T* residual) const {
    const T* const control_points[4] = {s0, s1, s2, s3};
    const SE3<T> T_W_C = evaluateSe3Spline(control_points, T(u));
    const Eigen::Quaternion<T> error = q_B_W_measured.cast<T>() * T_W_C.q * q_C_B.cast<T>();
    const Vector3<T> r = logSO3(error);
    for (int k = 0; k < 3; ++k) residual[k] = r[k];
    return true;
  }
};

class SplineInsAttitudeFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 3;

  // Throws std::out_of_range when t_fix is outside the spline's valid range,
  // std::invalid_argument for a malformed timing, a noise model that is not
  // 3-dimensional or a measured attitude / T_B_C rotation that is not a unit
  // quaternion.
  SplineInsAttitudeFactor(const SplineTiming& spline, double t_fix,
                          const Eigen::Quaterniond& q_W_B_measured, const SE3d& T_B_C,
                          NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "SplineInsAttitudeFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  double fixTime() const { return t_fix_; }
  // Index i of S(i), the first active control point, and u in [0, 1].
  const SplineSegment& segment() const { return segment_; }
  const Eigen::Quaterniond& measuredAttitude() const { return q_W_B_measured_; }
  const SE3d& T_B_C() const { return T_B_C_; }

 private:
  double t_fix_;
  SplineSegment segment_;
  Eigen::Quaterniond q_W_B_measured_;
  SE3d T_B_C_;
};

}  // namespace hsmap
