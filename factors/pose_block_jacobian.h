#pragma once
// Ambient Jacobians of pose blocks for factors whose Jacobians are analytic
// (computed in the tangent space) rather than autodiffed.
//
// A factor with analytic Jacobians knows df/dxi, the derivative under the
// right perturbation T exp(xi) of a pose block (xi = [rho; phi], se3.h), but
// a ceres::CostFunction returns Jacobians with respect to the 7 ambient
// scalars [qx qy qz qw tx ty tz], which the solver's Se3Manifold
// (solvers/se3_manifold.h) multiplies by its PlusJacobian P (7x6). Returning
//   J_ambient = J_tangent M,   M = the manifold's MinusJacobian at the block,
//   M = [ 0 (3x4)                    R^T     ]
//       [ 2 [w I - hat(v) | -v]      0 (3x3) ]      (q = (w, v), R = R(q))
// makes J_ambient P = J_tangent exactly, because M P = I for a unit quaternion
// (the manifold keeps every pose block unit). J_ambient is therefore not the
// derivative with respect to the raw scalars (it has no component off the
// manifold): it is meaningful only through Se3Manifold's PlusJacobian, as
// every pose block of hsmap's solver is. factor_test_support.h checks factors
// exactly that way.

#include <Eigen/Core>

#include "core/geometry/se3.h"
#include "core/geometry/so3.h"

namespace hsmap {

// Writes J_tangent (Rows x 6, columns [rho phi]) as the ambient Jacobian
// (Rows x 7, row-major, columns [qx qy qz qw tx ty tz]) of the pose block
// holding T; see the header comment.
template <int Rows>
void poseTangentToAmbientJacobian(const SE3d& T, const Eigen::Matrix<double, Rows, 6>& J_tangent,
                                  double* J_ambient) {
  Eigen::Matrix<double, 3, 4> d_phi_d_q;
  d_phi_d_q.leftCols<3>() = 2.0 * (T.q.w() * Eigen::Matrix3d::Identity() - hat(T.q.vec()));
  d_phi_d_q.col(3) = -2.0 * T.q.vec();
  Eigen::Map<Eigen::Matrix<double, Rows, 7, Eigen::RowMajor>> out(J_ambient);
  out.template leftCols<4>().noalias() = J_tangent.template rightCols<3>() * d_phi_d_q;
  out.template rightCols<3>().noalias() =
      J_tangent.template leftCols<3>() * T.rotationMatrix().transpose();
}

}  // namespace hsmap
