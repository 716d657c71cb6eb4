#pragma once
// SplinePoseFactor: a measured camera pose T_W_C_measured at time t,
// constraining the trajectory spline there. Its use is initialisation: fit a
// spline to a list of timestamped poses (keyframe poses from visual odometry,
// INS poses composed with T_B_C) by one SplinePoseFactor per pose, before the
// spline enters a bundle adjustment.
//
//   variables  S(i), S(i+1), S(i+2), S(i+3): the four control points (poses
//              T_W_C, [qx qy qz qw tx ty tz]) active at t
//   model      T_W_C(t) = spline(S(i..i+3), u) (core/geometry/se3_bspline.h),
//              i, u from SplineTiming::segmentAt(t), fixed at construction
//   residual   r = log(T_W_C_measured^-1 * T_W_C(t)) = [rho; phi]     (6)
// with se3.h's log, TRANSLATION FIRST: rho (metres) and phi (radians), both in
// the camera frame C (right perturbation: T_W_C(t) = T_W_C_measured * exp(r)),
// as PosePriorFactor's, so the noise model's 6x6 covariance is that of a right
// perturbation of the measured pose, e.g.
// fromSigmas([sigma_t, sigma_t, sigma_t, sigma_r, sigma_r, sigma_r]).
//
// Why at the pose's own time: the measurement constrains the spline exactly
// where it was taken; rounding it to a knot or a frame time misplaces it by
// the motion in between (at 0.4 m/s a 20 ms mismatch is 8 mm).
//
// Jacobians: Ceres autodiff of SplinePoseResidual.

#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/spline_timing.h"

namespace hsmap {

// Ceres functor: (control points S(i..i+3) [7 each]) -> residual [6].
struct SplinePoseResidual {
  double u;  // normalised time of the measurement in segment i
  SE3d measured_inverse;  // T_W_C_measured^-1

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, T* residual) const {
    const T* const control_points[4] = {s0, s1, s2, s3};
    const Vector6<T> r =
        (measured_inverse.cast<T>() * evaluateSe3Spline(control_points, T(u))).log();
    for (int k = 0; k < 6; ++k) residual[k] = r[k];
    return true;
  }
};

class SplinePoseFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 6;

  // Throws std::out_of_range when t is outside the spline's valid range,
  // std::invalid_argument for a malformed timing, a noise model that is not
  // 6-dimensional or a measured pose whose rotation is not a unit quaternion
  // or whose translation is not finite.
  SplinePoseFactor(const SplineTiming& spline, double t, const SE3d& T_W_C_measured,
                   NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "SplinePoseFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  double time() const { return t_; }
  // Index i of S(i), the first active control point, and u in [0, 1].
  const SplineSegment& segment() const { return segment_; }
  const SE3d& measuredPose() const { return T_W_C_measured_; }

 private:
  double t_;
  SplineSegment segment_;
  SE3d T_W_C_measured_;
};

}  // namespace hsmap
