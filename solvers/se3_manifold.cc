#include "solvers/se3_manifold.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/geometry/se3.h"
#include "core/geometry/so3.h"

namespace hsmap {

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// d q / d phi of q * exp(phi) at phi = 0, rows [qx qy qz qw] (see the header).
Eigen::Matrix<double, 4, 3> quaternionPlusJacobian(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 4, 3> J;
  J.topRows<3>() = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + hat(q.vec()));
  J.bottomRows<1>() = -0.5 * q.vec().transpose();
  return J;
}

}  // namespace

bool Se3Manifold::Plus(const double* x, const double* delta, double* x_plus_delta) const {
  const SE3d T = SE3d::fromParameters(x);
  SE3d result = T * SE3d::exp(Eigen::Map<const Vector6d>(delta));
  result.q.normalize();
  result.toParameters(x_plus_delta);
  return true;
}

bool Se3Manifold::PlusJacobian(const double* x, double* jacobian) const {
  const SE3d T = SE3d::fromParameters(x);
  Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<4, 3>(0, 3) = quaternionPlusJacobian(T.q);
  J.block<3, 3>(4, 0) = T.rotationMatrix();
  return true;
}

bool Se3Manifold::RightMultiplyByPlusJacobian(const double* x, int num_rows,
                                              const double* ambient_matrix,
                                              double* tangent_matrix) const {
  // A * J with J block-sparse: [A_t R, A_q Jq]; avoids forming the zero blocks
  // of the 7x6 Jacobian for every residual block.
  if (num_rows == 0) return true;
  const SE3d T = SE3d::fromParameters(x);
  const Eigen::Map<const RowMajorMatrix> A(ambient_matrix, num_rows, kAmbientSize);
  Eigen::Map<RowMajorMatrix> out(tangent_matrix, num_rows, kTangentSize);
  out.leftCols<3>().noalias() = A.rightCols<3>() * T.rotationMatrix();
  out.rightCols<3>().noalias() = A.leftCols<4>() * quaternionPlusJacobian(T.q);
  return true;
}

bool Se3Manifold::Minus(const double* y, const double* x, double* y_minus_x) const {
  const SE3d T_x = SE3d::fromParameters(x);
  const SE3d T_y = SE3d::fromParameters(y);
  Eigen::Map<Vector6d> out(y_minus_x);
  out = (T_x.inverse() * T_y).log();
  return true;
}

bool Se3Manifold::MinusJacobian(const double* x, double* jacobian) const {
  const SE3d T = SE3d::fromParameters(x);
  Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> J(jacobian);
  J.setZero();
  J.block<3, 3>(0, 4) = T.rotationMatrix().transpose();
  J.block<3, 3>(3, 0) = 2.0 * (T.q.w() * Eigen::Matrix3d::Identity() - hat(T.q.vec()));
  J.block<3, 1>(3, 3) = -2.0 * T.q.vec();
  return true;
}

}  // namespace hsmap
