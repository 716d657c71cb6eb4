#pragma once
// PushbroomLineFactor: a 3D point seen by one pixel of one UHI scan line.
// This is the factor that ties the hyperspectral camera to the trajectory: it
// estimates the RGB-UHI extrinsic T_C_U and the UHI time offset d together
// with the spline.
//
//   variables  S(j) .. S(j+4): five consecutive control points of the
//                 trajectory spline of T_W_C (poses, [qx qy qz qw tx ty tz]),
//              e = T_C_U (pose, usually E(0)),
//              d (scalar, seconds, usually D(0)),
//              and, in the landmark form, l = p_W (point, m); in the
//              fixed-point form p_W is a constant (e.g. a point of the mesh
//              found by render-and-compare matching).
//   model      true exposure time t = t_recorded + d (DATASET.md), and
//              T_W_U = T_W_C(t) * T_C_U,   p_U = T_W_U^-1 p_W,
//              (u_pred, y_U / z_U) = pushbroom projection of p_U
//              (core/geometry/pushbroom_camera.h, fixed intrinsics).
//   residual   r = [u_pred - u_measured ;     (pixels along the line)
//                   y_U / z_U ]               (tangent of the across-line angle)
// A scan line only sees points with y_U = 0, so the second component is the
// across-line offset; its sigma in the noise model is the instantaneous field
// of view (e.g. half a pixel's angle, 0.5 / f), typically
// NoiseModel::fromSigmas([sigma_u_px, sigma_across]).
//
// Time offset. The spline's normalised time is
//   s = (t_recorded + d - t0) / dt - j   (knot units from S(j))
// and it is computed from the variable d at every evaluation, so the
// derivative with respect to d (through the spline's u) is exact.
//
// Which control points. The pose at time t depends on the four control points
// of t's segment, and that segment moves when d does. The factor therefore
// spans TWO consecutive segments (five control points), chosen at
// construction from the initial guess d0 so that t_recorded + d0 is at least
// half a knot interval away from both ends of the window (except where the
// spline itself ends). At every evaluation the functor picks the segment of
// the current s (the spline is C2 across the knot, so the choice keeps the
// residual smooth); the control point outside the current segment gets a zero
// Jacobian. If d moves further than the window covers (coversTimeOffset()
// turns false; in practice |d - d0| > dt / 2), the pose is extrapolated by
// the segment's polynomial, which is no longer the spline: the caller must
// rebuild the factor with the new d. The spline needs N >= 5 control points.
//
// Behind the camera: z_U goes through softPositiveDepth() (positive_depth.h),
// so the residual stays finite.
//
// Jacobians. createCostFunction() evaluates them analytically: with G_U the
// projection's Jacobian under T_W_U exp(xi) (world_point_projection_jacobians.h),
//   T_C_U:                   G_U   (T_W_C T_C_U exp(xi) = T_W_U exp(xi)),
//   the segment's 4 points:  G_C = G_U Ad(T_C_U^-1) through the spline's
//                            control-point Jacobians (se3_bspline_jacobians.h),
//   d:                       G_C xi_u / dt (xi_u the spline's body twist per
//                            unit u: dT_W_C/dd = T_W_C hat(xi_u) / dt),
//   p_W:                     the projection's point Jacobian,
// with the pose blocks' Jacobians in the form of pose_block_jacobian.h (exact
// through the solver's Se3Manifold): ~1.9 us per evaluation against ~50 us
// for autodiff (benchmarks/factors_bench.cc). createAutoDiffCostFunction() is
// the autodiff of PushbroomLineResidual below, the reference the tests compare with.

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/scalar_part.h"
#include "factors/spline_timing.h"
#include "factors/world_point_projection.h"

namespace hsmap {

// One scan-line pixel observation.
struct PushbroomObservation {
  double t_recorded = 0.0;  // s, the line's time stamp in lines.csv (true time minus d)
  double u = 0.0;           // pixel along the line (centre of the first pixel at 0)
};

// Ceres functor for both forms:
//   fixed point: (S(j..j+4) [7 each], T_C_U [7], d [1]) -> residual [2]
//   landmark:    (S(j..j+4) [7 each], T_C_U [7], d [1], p_W [3]) -> residual [2]
struct PushbroomLineResidual {
  double s_recorded;  // (t_recorded - t0) / dt - j
  double inverse_dt;  // 1 / dt
  double u_measured;
  std::array<double, PushbroomCamera::kNumIntrinsics> intrinsics;
  Eigen::Vector3d p_W_fixed;  // used by the fixed-point form only

  // (u_pred, y_U / z_U) for the window's five control points.
  template <class T>
  Vector2<T> predict(const T* const* window, const T* extrinsic_T_C_U, const T* time_offset_d,
                     const Vector3<T>& p_W) const {
    std::array<T, PushbroomCamera::kNumIntrinsics> k;
    for (int i = 0; i < PushbroomCamera::kNumIntrinsics; ++i) k[i] = T(intrinsics[i]);
    return predictWith(window, extrinsic_T_C_U, time_offset_d, p_W, k.data());
  }

  // predict() with the intrinsics [f cx k1 k2] given (a variable block of a
  // self-calibrating factor) instead of the constant `intrinsics`.
  template <class T>
  Vector2<T> predictWith(const T* const* window, const T* extrinsic_T_C_U, const T* time_offset_d,
                         const Vector3<T>& p_W, const T* uhi_intrinsics) const {
    const T s = T(s_recorded) + time_offset_d[0] * inverse_dt;
    const int segment = scalarPart(s) < 1.0 ? 0 : 1;
    const SE3<T> T_W_C = evaluateSe3Spline(window + segment, T(s - double(segment)));
    const SE3<T> T_W_U = T_W_C * SE3<T>::fromParameters(extrinsic_T_C_U);
    return projectPushbroom(T_W_U, p_W, uhi_intrinsics);
  }

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, const T* s4,
                  const T* extrinsic_T_C_U, const T* time_offset_d, T* residual) const {
    const T* const window[5] = {s0, s1, s2, s3, s4};
    const Vector2<T> predicted =
        predict(window, extrinsic_T_C_U, time_offset_d, Vector3<T>(p_W_fixed.cast<T>()));
    residual[0] = predicted.x() - u_measured;
    residual[1] = predicted.y();
    return true;
  }

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, const T* s4,
                  const T* extrinsic_T_C_U, const T* time_offset_d, const T* landmark_p_W,
                  T* residual) const {
    const T* const window[5] = {s0, s1, s2, s3, s4};
    const Vector2<T> predicted =
        predict(window, extrinsic_T_C_U, time_offset_d,
                Vector3<T>(landmark_p_W[0], landmark_p_W[1], landmark_p_W[2]));
    residual[0] = predicted.x() - u_measured;
    residual[1] = predicted.y();
    return true;
  }
};

class PushbroomLineFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;
  static constexpr int kNumControlPoints = 5;

  // Landmark form: keys S(j..j+4), extrinsic_T_C_U, time_offset_d, landmark_p_W.
  // Throws std::out_of_range when t_recorded + time_offset_guess_s is outside
  // the spline's valid range; std::invalid_argument for a spline of fewer than
  // 5 control points, a noise model that is not 2-dimensional, a non-finite
  // observation or invalid camera parameters.
  PushbroomLineFactor(const SplineTiming& spline, double time_offset_guess_s,
                      Key extrinsic_T_C_U, Key time_offset_d, Key landmark_p_W,
                      const PushbroomObservation& observation, const PushbroomParameters& camera,
                      NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());
  // Fixed-point form: keys S(j..j+4), extrinsic_T_C_U, time_offset_d; p_W is
  // a constant (also checked finite).
  PushbroomLineFactor(const SplineTiming& spline, double time_offset_guess_s,
                      Key extrinsic_T_C_U, Key time_offset_d, const Eigen::Vector3d& p_W,
                      const PushbroomObservation& observation, const PushbroomParameters& camera,
                      NoiseModel noise, RobustLoss robust_loss = RobustLoss::none());

  // j of the window S(j) .. S(j+4) a factor built with these arguments uses
  // (the same checks and errors as the constructors).
  static int windowStartFor(const SplineTiming& spline, double t_recorded,
                            double time_offset_guess_s);
  // The keys S(first) .. S(first+4), extrinsic_T_C_U, time_offset_d.
  static std::vector<Key> windowKeysFor(int first, Key extrinsic_T_C_U, Key time_offset_d);

  std::string name() const override { return "PushbroomLineFactor"; }
  // Analytic Jacobians (see the header comment).
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;
  // The same residual through ceres::AutoDiffCostFunction (reference for tests
  // and benchmarks; true ambient derivatives).
  std::unique_ptr<ceres::CostFunction> createAutoDiffCostFunction() const;

  const PushbroomObservation& observation() const { return observation_; }
  bool hasLandmark() const { return !p_W_fixed_.has_value(); }
  // The constant point of the fixed-point form (std::nullopt in the landmark form).
  const std::optional<Eigen::Vector3d>& fixedPoint() const { return p_W_fixed_; }
  // j: the window is S(j) .. S(j+4).
  int firstControlPoint() const { return first_control_point_; }
  // [begin, end] of true exposure times t_recorded + d the window represents
  // exactly (two knot intervals).
  std::pair<double, double> coveredTimeRange() const;
  // Whether the factor is still exact for time offset d (else rebuild it).
  bool coversTimeOffset(double d) const;

 private:
  PushbroomLineFactor(const SplineTiming& spline, int first_control_point,
                      std::vector<Key> keys, std::optional<Eigen::Vector3d> p_W_fixed,
                      const PushbroomObservation& observation, const PushbroomParameters& camera,
                      NoiseModel noise, RobustLoss robust_loss);

  SplineTiming spline_;
  int first_control_point_;
  std::optional<Eigen::Vector3d> p_W_fixed_;
  PushbroomObservation observation_;
  PushbroomCamera camera_;
};

}  // namespace hsmap
