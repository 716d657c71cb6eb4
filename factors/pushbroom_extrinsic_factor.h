#pragma once
// PushbroomExtrinsicFactor: a known 3D point seen by one pixel of one UHI scan
// line whose RGB-camera pose is known; only the extrinsic T_C_U is estimated.
// This is the factor of the products-stage extrinsic refinement
// (pipelines/calibration/extrinsic_refinement.h), where the line poses come
// from the run's trajectory and the points from the RGB ortho-image's mesh.
//
//   variable   e = T_C_U (pose, usually E(0))
//   constants  T_W_C of the line (the RGB camera at the line's true time),
//              p_W (a point of the mesh), the observed sample u, the UHI
//              intrinsics
//   model      T_W_U = T_W_C * T_C_U,   p_U = T_W_U^-1 p_W,
//              (u_pred, y_U / z_U) = pushbroom projection of p_U
//              (core/geometry/pushbroom_camera.h)
//   residual   r = [u_pred - u ;       (pixels along the line)
//                   y_U / z_U ]        (tangent of the across-line angle)
// the same residual as PushbroomLineFactor (pushbroom_line_factor.h) with the
// spline and the time offset frozen. Its noise is typically
// NoiseModel::fromSigmas([sigma_u_px, sigma_across]), sigma_across the
// across-line angle (radians) a match's error amounts to.
//
// Behind the camera: z_U goes through softPositiveDepth() (positive_depth.h).
// Jacobian: Ceres automatic differentiation (one 7-parameter block; cheap).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"
#include "factors/world_point_projection.h"

namespace hsmap {

// Ceres functor: (T_C_U [7]) -> residual [2].
struct PushbroomExtrinsicResidual {
  SE3d T_W_C;
  Eigen::Vector3d p_W;
  double u_measured;
  std::array<double, PushbroomCamera::kNumIntrinsics> intrinsics;

  template <class T>
  bool operator()(const T* extrinsic_T_C_U, T* residual) const {
    const SE3<T> T_W_U = T_W_C.cast<T>() * SE3<T>::fromParameters(extrinsic_T_C_U);
    std::array<T, PushbroomCamera::kNumIntrinsics> k;
    for (int i = 0; i < PushbroomCamera::kNumIntrinsics; ++i) k[i] = T(intrinsics[i]);
    const Vector2<T> predicted = projectPushbroom(T_W_U, Vector3<T>(p_W.cast<T>()), k.data());
    residual[0] = predicted.x() - u_measured;
    residual[1] = predicted.y();
    return true;
  }
};

class PushbroomExtrinsicFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 2;

  // Throws std::invalid_argument for a noise model that is not 2-dimensional,
  // a line pose whose rotation is not a unit quaternion, a non-finite point
  // or sample, or invalid camera parameters.
  PushbroomExtrinsicFactor(Key extrinsic_T_C_U, const SE3d& T_W_C, const Eigen::Vector3d& p_W,
                           double u_measured, const PushbroomParameters& camera, NoiseModel noise,
                           RobustLoss robust_loss = RobustLoss::none());

  std::string name() const override { return "PushbroomExtrinsicFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const SE3d& lineCameraPose() const { return T_W_C_; }
  const Eigen::Vector3d& point() const { return p_W_; }
  double sample() const { return u_measured_; }

 private:
  SE3d T_W_C_;
  Eigen::Vector3d p_W_;
  double u_measured_;
  PushbroomCamera camera_;
};

}  // namespace hsmap
