#pragma once
// PushbroomCameraPointFactor: a UHI pixel of one scan line saw a point that
// is known in the RGB camera's frame at a reference time t_ref (e.g. a point
// of the surface that the RGB frames around the line's time triangulated).
// It is PushbroomLineFactor's fixed-point form with the point carried along
// by the trajectory instead of fixed in W:
//
//   variables  S(j) .. S(j+4) (the window of PushbroomLineFactor for the
//              line's recorded time and the time-offset guess), e = T_C_U,
//              d (scalar, seconds)
//   constants  p_C (the point in C at t_ref), t_ref (inside the window's two
//              segments), the observed sample u, the UHI intrinsics
//   model      p_W = T_W_C(t_ref) p_C,
//              T_W_U = T_W_C(t_recorded + d) T_C_U,  p_U = T_W_U^-1 p_W,
//   residual   r = [u_pred - u ; y_U / z_U]    (as PushbroomLineFactor)
//
// Why. A fixed p_W ties the UHI to the frame W the point was expressed in.
// When the trajectory is re-estimated with it (the joint problem), the whole
// trajectory may settle a few centimetres away from where the point's map
// was made (the INS fixes the absolute position only to decimetres), and a
// fixed p_W would then pull T_C_U by that offset. A point carried by the
// trajectory sees only the relative motion between t_ref and the line's
// exposure, which is what the tie point measured.
//
// Self-calibrating form: the UHI intrinsics [f cx k1 k2]
// (PushbroomCamera::kNumIntrinsics, usually K(0), shared by every tie point)
// are a variable block after d instead of constants, so the tie points across
// the whole swath measure the lens model too (docs/JOINT.md, "The push-broom
// camera's intrinsics"). The fixed form is unchanged (same functor, same cost).
//
// Jacobians: Ceres automatic differentiation (a few hundred to a few
// thousand such factors per solve).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/pushbroom_line_factor.h"
#include "factors/spline_timing.h"

namespace hsmap {

// Ceres functor: (S(j..j+4) [7 each], T_C_U [7], d [1]) -> residual [2].
struct PushbroomCameraPointResidual {
  PushbroomLineResidual line;  // its p_W_fixed is unused
  double s_reference;          // (t_ref - t0) / dt - j, in [0, 2]
  Eigen::Vector3d p_C;

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, const T* s4,
                  const T* extrinsic_T_C_U, const T* time_offset_d, T* residual) const {
    const T* const window[5] = {s0, s1, s2, s3, s4};
    const int segment = s_reference < 1.0 ? 0 : 1;
    const SE3<T> T_W_C_reference = evaluateSe3Spline(window + segment, T(s_reference - segment));
    const Vector3<T> p_W = T_W_C_reference * Vector3<T>(p_C.cast<T>());
    const Vector2<T> predicted = line.predict(window, extrinsic_T_C_U, time_offset_d, p_W);
    residual[0] = predicted.x() - line.u_measured;
    residual[1] = predicted.y();
    return true;
  }
};

// Ceres functor of the self-calibrating form: (S(j..j+4) [7 each], T_C_U [7],
// d [1], intrinsics [4]) -> residual [2].
struct PushbroomCameraPointIntrinsicsResidual {
  PushbroomCameraPointResidual point;  // its line.intrinsics are unused

  template <class T>
  bool operator()(const T* s0, const T* s1, const T* s2, const T* s3, const T* s4,
                  const T* extrinsic_T_C_U, const T* time_offset_d, const T* uhi_intrinsics,
                  T* residual) const {
    const T* const window[5] = {s0, s1, s2, s3, s4};
    const int segment = point.s_reference < 1.0 ? 0 : 1;
    const SE3<T> T_W_C_reference =
        evaluateSe3Spline(window + segment, T(point.s_reference - segment));
    const Vector3<T> p_W = T_W_C_reference * Vector3<T>(point.p_C.cast<T>());
    const Vector2<T> predicted =
        point.line.predictWith(window, extrinsic_T_C_U, time_offset_d, p_W, uhi_intrinsics);
    residual[0] = predicted.x() - point.line.u_measured;
    residual[1] = predicted.y();
    return true;
  }
};

class PushbroomCameraPointFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;

  // Keys S(j..j+4), extrinsic_T_C_U, time_offset_d (j as PushbroomLineFactor
  // chooses it). Throws std::out_of_range when t_reference is outside the
  // window's two segments or the exposure time is outside the spline, and
  // std::invalid_argument for what PushbroomLineFactor rejects or a
  // non-finite p_C.
  PushbroomCameraPointFactor(const SplineTiming& spline, double time_offset_guess_s,
                             Key extrinsic_T_C_U, Key time_offset_d, double t_reference,
                             const Eigen::Vector3d& p_C, const PushbroomObservation& observation,
                             const PushbroomParameters& camera, NoiseModel noise,
                             RobustLoss robust_loss = RobustLoss::none());
  // Self-calibrating form: keys S(j..j+4), extrinsic_T_C_U, time_offset_d,
  // uhi_intrinsics (a vector of PushbroomCamera::kNumIntrinsics). `camera`
  // still gives the window's checks and the residual's sample count; its
  // intrinsics are not used by the residual.
  PushbroomCameraPointFactor(const SplineTiming& spline, double time_offset_guess_s,
                             Key extrinsic_T_C_U, Key time_offset_d, Key uhi_intrinsics,
                             double t_reference, const Eigen::Vector3d& p_C,
                             const PushbroomObservation& observation,
                             const PushbroomParameters& camera, NoiseModel noise,
                             RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "PushbroomCameraPointFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  int firstControlPoint() const { return first_control_point_; }
  double referenceTime() const { return t_reference_; }
  const Eigen::Vector3d& pointInCamera() const { return p_C_; }
  const PushbroomObservation& observation() const { return observation_; }
  bool estimatesIntrinsics() const { return estimates_intrinsics_; }

 private:
  static std::vector<Key> keysFor(const SplineTiming& spline, double time_offset_guess_s,
                           Key extrinsic_T_C_U, Key time_offset_d, const std::optional<Key>& uhi_intrinsics,
                           const PushbroomObservation& observation);
  PushbroomCameraPointFactor(const SplineTiming& spline, double time_offset_guess_s,
                             Key extrinsic_T_C_U, Key time_offset_d,
                             const std::optional<Key>& uhi_intrinsics, double t_reference,
                             const Eigen::Vector3d& p_C, const PushbroomObservation& observation,
                             const PushbroomParameters& camera, NoiseModel noise,
                             RobustLoss robust_loss);
  PushbroomCameraPointResidual residual() const;

  SplineTiming spline_;
  int first_control_point_;
  double t_reference_;
  Eigen::Vector3d p_C_;
  PushbroomObservation observation_;
  PushbroomCamera camera_;
  bool estimates_intrinsics_ = false;
};

}  // namespace hsmap
