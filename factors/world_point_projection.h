#pragma once
// Projection of a world point through a posed camera, shared by the camera
// factors so that they all treat frames and depth the same way:
//   p_C = T_W_C^-1 p_W = R_W_C^T (p_W - t_W_C)
// then the camera model of core/geometry, with the depth passed through
// softPositiveDepth() (positive_depth.h) so that points at or behind the
// camera give finite residuals.
//
//   projectPinhole:   pixel (u, v) of the RGB camera (PinholeRadtanCamera),
//                     intrinsics [fx fy cx cy k1 k2 p1 p2 k3]
//   projectPushbroom: (u, y_U / z_U) of the UHI line camera (PushbroomCamera),
//                     intrinsics [f cx k1 k2]
// Templated on the scalar for Ceres autodiff.

#include "core/geometry/matrix_types.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "factors/positive_depth.h"

namespace hsmap {

// p_A = T_W_A^-1 p_W with the depth floored (see positive_depth.h).
template <class T>
Vector3<T> pointInCameraWithPositiveDepth(const SE3<T>& T_W_A, const Vector3<T>& p_W) {
  Vector3<T> p_A = T_W_A.q.conjugate() * Vector3<T>(p_W - T_W_A.t);
  p_A.z() = softPositiveDepth(p_A.z());
  return p_A;
}

template <class T>
Vector2<T> projectPinhole(const SE3<T>& T_W_C, const Vector3<T>& p_W, const T* intrinsics) {
  return PinholeRadtanCamera::projectWith(intrinsics, pointInCameraWithPositiveDepth(T_W_C, p_W));
}

template <class T>
Vector2<T> projectPushbroom(const SE3<T>& T_W_U, const Vector3<T>& p_W, const T* intrinsics) {
  return PushbroomCamera::projectWith(intrinsics, pointInCameraWithPositiveDepth(T_W_U, p_W));
}

}  // namespace hsmap
