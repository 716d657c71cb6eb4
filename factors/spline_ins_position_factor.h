#pragma once
// SplineInsPositionFactor: the INS position fix of the body B at its own time
// t_fix, constraining the trajectory spline through the known lever arm T_B_C
// (InsPositionFactor's model with the pose taken from the spline).
//
//   variables  S(i), S(i+1), S(i+2), S(i+3): the four control points (poses
//              T_W_C, [qx qy qz qw tx ty tz]) active at t_fix
//   model      T_W_C(t_fix) = spline(S(i..i+3), u) (core/geometry/se3_bspline.h),
//              i, u from SplineTiming::segmentAt(t_fix), fixed at construction;
//              T_W_B = T_W_C(t_fix) * T_B_C^-1, so
//              t_W_B = R_W_C(t_fix) t_C_B + t_W_C(t_fix), T_C_B = T_B_C^-1
//   residual   r = t_W_B - p_W_B_measured                  (3, metres, in W)
// W is the local North-East-Down frame, so a noise model from the survey's
// sigmas is fromSigmas([sigma_horizontal, sigma_horizontal, sigma_depth]).
//
// Why at the fix's own time: a keyframe InsPositionFactor needs the fix
// interpolated to the frame time, or it attaches the fix to the wrong pose; at
// a survey speed of 0.4 m/s a 20 ms mismatch is 8 mm, comparable to the depth
// sensor's sigma. On the spline the fix constrains the pose at exactly the
// time it was measured (its timestamp must be on the spline's clock).
//
// Jacobians: Ceres autodiff of SplineInsPositionResidual (true ambient
// derivatives; the solver's Se3Manifold maps them to the tangent space).

#include <Eigen/Core>
#include <memory>
#include <string>

#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/spline_timing.h"

namespace hsmap {

// Ceres functor: (control points S(i..i+3) [7 each]) -> residual [3].
struct SplineInsPositionResidual {
  double u;  // normalised time of the fix in segment i
  Eigen::Vector3d p_W_B_measured;
  Eigen::Vector3d t_C_B;  // translation of T_C_B = T_B_C^-1 (origin of B in C)

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, T* residual) const {
    const T* const control_points[4] = {s0, s1, s2, s3};
    const SE3<T> T_W_C = evaluateSe3Spline(control_points, T(u));
    const Vector3<T> t_W_B = T_W_C * Vector3<T>(t_C_B.cast<T>());
    for (int k = 0; k < 3; ++k) residual[k] = t_W_B[k] - p_W_B_measured[k];
    return true;
  }
};

class SplineInsPositionFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 3;

  // Throws std::out_of_range when t_fix is outside the spline's valid range,
  // std::invalid_argument for a malformed timing, a noise model that is not
  // 3-dimensional, a non-finite fix or a T_B_C whose rotation is not a unit
  // quaternion.
  SplineInsPositionFactor(const SplineTiming& spline, double t_fix,
                          const Eigen::Vector3d& p_W_B_measured, const SE3d& T_B_C,
                          NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "SplineInsPositionFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  double fixTime() const { return t_fix_; }
  // Index i of S(i), the first active control point, and u in [0, 1].
  const SplineSegment& segment() const { return segment_; }
  const Eigen::Vector3d& measuredPosition() const { return p_W_B_measured_; }
  const SE3d& T_B_C() const { return T_B_C_; }

 private:
  double t_fix_;
  SplineSegment segment_;
  Eigen::Vector3d p_W_B_measured_;
  SE3d T_B_C_;
};

}  // namespace hsmap
