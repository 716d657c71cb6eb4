#pragma once
// Se3Manifold: the ceres::Manifold of a pose block [qx qy qz qw tx ty tz]
// (core/graph/values.h, core/geometry/se3.h), with the RIGHT perturbation of
// se3.h:
//
//   x (+) xi = x * exp(xi),      xi = [rho; phi]  (translation first),
//   y (-) x  = log(x^-1 * y),
//
// where exp/log are SE3d::exp/log (the full SE(3) exponential: the
// translation of exp(xi) is Jl(phi) rho, not rho). A step xi is therefore a
// motion expressed in the pose's own frame (the body frame B of T_W_B), and
// the 6x6 marginal covariance of a pose (solvers/marginal_covariance.h) is the
// covariance of that body-frame perturbation, in [rho; phi] order (metres,
// radians). The factors' numeric Jacobian tests perturb poses the same way.
//
// Jacobians at xi = 0 (x = (q, t), q = (w, v), R = R(q)):
//   PlusJacobian (7x6, rows [qx qy qz qw tx ty tz], columns [rho phi]):
//     d q / d phi = 1/2 [w I + hat(v); -v^T]   (q * (1, phi/2) to first order)
//     d t / d rho = R,  d t / d phi = 0,  d q / d rho = 0
//   MinusJacobian (6x7, d(y (-) x)/dy at y = x):
//     d rho / d t_y = R^T
//     d phi / d v_y = 2 (w I - hat(v)),  d phi / d w_y = -2 v
//   (2 vec(q^-1 q_y) to first order), so MinusJacobian * PlusJacobian = I.
//
// Minus takes the shorter arc (log returns angles in [0, pi]), so q and -q are
// the same pose; Plus keeps the quaternion's sign as it comes out of the
// product and renormalises it, so rounding never lets it drift off the unit
// sphere over many iterations.

#include <ceres/manifold.h>

namespace hsmap {

class Se3Manifold final : public ceres::Manifold {
 public:
  static constexpr int kAmbientSize = 7;
  static constexpr int kTangentSize = 6;

  int AmbientSize() const override { return kAmbientSize; }
  int TangentSize() const override { return kTangentSize; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override;
  bool PlusJacobian(const double* x, double* jacobian) const override;
  bool RightMultiplyByPlusJacobian(const double* x, int num_rows, const double* ambient_matrix,
                                   double* tangent_matrix) const override;
  bool Minus(const double* y, const double* x, double* y_minus_x) const override;
  bool MinusJacobian(const double* x, double* jacobian) const override;
};

}  // namespace hsmap
