#pragma once
// projectWithJacobians(): the projection of world_point_projection.h (a world
// point through a posed camera, depth floored by softPositiveDepth()) with its
// analytic Jacobians, for factors that do not autodiff.
//
// For a camera A at T_W_A = (R, t) and a world point p_W:
//   p_A = R^T (p_W - t),  p_eff = (x_A, y_A, softPositiveDepth(z_A)),
//   r = Camera::projectWith(intrinsics, p_eff).
// Under the right perturbation T_W_A exp(xi), xi = [rho; phi] (se3.h),
//   p_A(xi) = exp(-xi) p_A ~= p_A - rho - phi x p_A,
// so d p_A / d xi = [-I, hat(p_A)] and d p_A / d p_W = R^T. The depth floor's
// slope is 1 for z >= z_min and z_min^2 / (2 z_min - z)^2 below (the branch
// softPositiveDepth() takes at z = z_min exactly is the first). d r / d p_eff
// is the camera model's own projectJacobianPoint().
//
// The value is computed with the same operations as projectPinhole() /
// projectPushbroom(), so it is identical to theirs to the last bit.

#include <Eigen/Core>

#include "core/geometry/se3.h"
#include "core/geometry/so3.h"
#include "factors/positive_depth.h"

namespace hsmap {

struct ProjectionJacobians {
  Eigen::Matrix<double, 2, 6> d_pose;   // d r / d xi under T_W_A exp(xi)
  Eigen::Matrix<double, 2, 3> d_point;  // d r / d p_W
};

// d softPositiveDepth(z) / dz.
inline double softPositiveDepthSlope(double z) {
  if (z >= kMinimumDepthM) return 1.0;
  const double denominator = 2.0 * kMinimumDepthM - z;
  return kMinimumDepthM * kMinimumDepthM / (denominator * denominator);
}

// Camera: PinholeRadtanCamera or PushbroomCamera. jacobians may be null.
template <class Camera>
Eigen::Vector2d projectWithJacobians(const Camera& camera, const SE3d& T_W_A,
                                     const Eigen::Vector3d& p_W, ProjectionJacobians* jacobians) {
  const Eigen::Vector3d p_A = T_W_A.q.conjugate() * Eigen::Vector3d(p_W - T_W_A.t);
  Eigen::Vector3d p_eff = p_A;
  p_eff.z() = softPositiveDepth(p_A.z());
  const Eigen::Vector2d r = Camera::projectWith(camera.intrinsics().data(), p_eff);
  if (jacobians != nullptr) {
    Eigen::Matrix<double, 2, 3> d_r_d_p_A = camera.projectJacobianPoint(p_eff);
    d_r_d_p_A.col(2) *= softPositiveDepthSlope(p_A.z());
    jacobians->d_pose.leftCols<3>() = -d_r_d_p_A;
    jacobians->d_pose.rightCols<3>().noalias() = d_r_d_p_A * hat(p_A);
    jacobians->d_point.noalias() = d_r_d_p_A * T_W_A.rotationMatrix().transpose();
  }
  return r;
}

}  // namespace hsmap
