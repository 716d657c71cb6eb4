#pragma once
// SE3SplineJacobians: the pose of the cumulative cubic SE(3) B-spline
// (se3_bspline.h) at one normalised time u, with its analytic derivatives:
// with respect to RIGHT perturbations of the four active control points
// (T_k (+) delta = T_k exp(delta), se3.h's convention and the solver's) and
// with respect to u. For factors that need the spline's Jacobians without
// autodiff (Sommer, Usenko, Schubert, Demmel, Cremers, "Efficient Derivative
// Computation for Cumulative B-Splines on Lie Groups", CVPR 2020).
//
// Derivation. T(u) = T_0 A_1 A_2 A_3 with A_j = exp(b_j Omega_j),
// Omega_j = log(D_j), D_j = T_{j-1}^-1 T_j and b_j = Bt_j(u) (control points
// numbered 0..3 within the segment). Perturbing the pose on the right at the
// position just after A_j moves the end pose by Ad(R_j^-1) of it, with
// R_j = A_{j+1} ... A_3 (R_3 = I, R_0 = A_1 A_2 A_3). With se3.h's
//   exp(x + d) ~= exp(x) exp(Jr(x) d),
//   log(D exp(delta)) ~= log(D) + Jr(Omega)^-1 delta,
//   log(exp(-delta) D) ~= log(D) - Jl(Omega)^-1 delta,
// a right perturbation delta_k of T_k changes Omega_k by Jr(Omega_k)^-1 delta_k
// and Omega_{k+1} by -Jl(Omega_{k+1})^-1 delta_k, so
//   T(u; T_k exp(delta_k)) = T(u) exp(J_k delta_k + O(|delta_k|^2)),
//   J_k = [k = 0] Ad(R_0^-1)
//       + [k >= 1] Ad(R_k^-1) b_k Jr(b_k Omega_k) Jr(Omega_k)^-1
//       - [k <= 2] Ad(R_{k+1}^-1) b_{k+1} Jr(b_{k+1} Omega_{k+1}) Jl(Omega_{k+1})^-1.
// Jl(Omega)^-1 = Jr(Omega)^-1 Ad(D^-1) (from Jl = Ad(exp(Omega)) Jr), so each
// term needs only Jr(b Omega) and Jr(Omega)^-1. chain() applies the J_k to the
// Jacobian of a function of the pose from the left (rows x 6 products, no 6x6
// products), walking j = 3 .. 1 and carrying G_j = G Ad(R_j^-1) as
// G_{j-1} = G_j Ad(A_j^-1) (Sommer et al.'s recursion).
//
// Time. dT/du = T hat(xi_u) with the body twist per unit u
//   xi_u = sum_j Ad(R_j^-1) dBt_j/du Omega_j,
// i.e. the velocity recursion of se3_bspline.h with dt = 1
// (xi_0 = 0, xi_j = Ad(A_j^-1) xi_{j-1} + dBt_j/du Omega_j): divide by dt for
// the twist per second.
//
// The pose is computed with the same operations in the same order as
// evaluateSe3SplinePose(), so both agree to the last bit. u outside [0, 1]
// extends the segment's polynomial, as there. Double precision only (the point
// is to avoid autodiff); the quaternions of the control points must be unit.

#include <Eigen/Core>
#include <array>

#include "core/geometry/matrix_types.h"
#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "core/geometry/so3.h"

namespace hsmap {

class SE3SplineJacobians {
 public:
  // Control points T_i .. T_{i+3} of the segment, normalised time u.
  SE3SplineJacobians(const std::array<SE3d, 4>& control_points, double u) {
    spline_detail::cumulativeBasis<double>(u, &b_, &db_, nullptr);
    pose_ = control_points[0];
    for (int j = 1; j <= 3; ++j) {
      D_[j] = control_points[j - 1].inverse() * control_points[j];
      Omega_[j] = D_[j].log();
      A_[j] = SE3d::exp(Vector6d(b_[j] * Omega_[j]));
      pose_ = pose_ * A_[j];
    }
  }

  // From four 7-scalar Ceres blocks [qx qy qz qw tx ty tz] (se3.h).
  static SE3SplineJacobians fromBlocks(const double* const* blocks, double u) {
    return SE3SplineJacobians({SE3d::fromParameters(blocks[0]), SE3d::fromParameters(blocks[1]),
                               SE3d::fromParameters(blocks[2]), SE3d::fromParameters(blocks[3])},
                              u);
  }

  // T(u), e.g. T_W_C at the time.
  const SE3d& pose() const { return pose_; }

  // xi_u: dT/du = T hat(xi_u) ([rho; phi] per unit of u; divide by dt for per second).
  Vector6d bodyTwistPerUnitU() const {
    Vector6d twist = Vector6d::Zero();
    for (int j = 1; j <= 3; ++j) {
      twist = A_[j].inverse().adjointTimes(twist) + db_[j] * Omega_[j];
    }
    return twist;
  }

  // Chain rule through the spline: given d_f_d_pose = df/dxi (Rows x 6) of a
  // function f of the pose under T(u) exp(xi), writes df/d delta_k =
  // d_f_d_pose * J_k for the four control points (see the header comment).
  template <int Rows>
  void chain(const Eigen::Matrix<double, Rows, 6>& d_f_d_pose,
             std::array<Eigen::Matrix<double, Rows, 6>, 4>* d_f_d_control_points) const {
    using RowsBy6 = Eigen::Matrix<double, Rows, 6>;
    std::array<RowsBy6, 4>& out = *d_f_d_control_points;
    RowsBy6 G = d_f_d_pose;  // G_3 = G Ad(R_3^-1) = G
    out[3].setZero();
    for (int j = 3; j >= 1; --j) {
      const RowsBy6 H = timesRightJacobian<Rows>(b_[j] * G, Vector6d(b_[j] * Omega_[j]));
      const RowsBy6 H_right = timesRightJacobianInverse<Rows>(H, Omega_[j]);
      out[j] += H_right;
      // Jl(Omega)^-1 = Jr(Omega)^-1 Ad(D^-1).
      out[j - 1] = -timesAdjoint<Rows>(H_right, D_[j].inverse());
      G = timesAdjoint<Rows>(G, A_[j].inverse());  // G_{j-1}
    }
    out[0] += G;
  }

  // The 6x6 J_k themselves: T(u; T_k exp(delta)) = T(u) exp(J_k delta).
  std::array<Matrix6d, 4> controlPointJacobians() const {
    std::array<Matrix6d, 4> J;
    chain<6>(Matrix6d::Identity(), &J);
    return J;
  }

 private:
  // Products of a Rows x 6 matrix M = [M_rho M_phi] with the block-triangular
  // 6x6 matrices of se3.h, without forming them (this runs once per residual
  // block and evaluation in the spline factors):
  //   Ad(X) = [R, hat(t) R; 0, R]                       for X = (R, t),
  //   Jr(x) = Jl(-x) = [Jr(phi), Q(-rho, -phi); 0, Jr(phi)],
  //   Jr(x)^-1 = [Jr(phi)^-1, -Jr(phi)^-1 Q(-rho, -phi) Jr(phi)^-1; 0, Jr(phi)^-1]
  // (SO(3) Jacobians of so3.h, Q of se3.h, x = [rho; phi]).
  template <int Rows>
  static Eigen::Matrix<double, Rows, 6> timesAdjoint(const Eigen::Matrix<double, Rows, 6>& M,
                                                     const SE3d& X) {
    const Eigen::Matrix3d R = X.rotationMatrix();
    Eigen::Matrix<double, Rows, 6> out;
    out.template leftCols<3>().noalias() = M.template leftCols<3>() * R;
    const Eigen::Matrix<double, Rows, 3> M_rho_hat_t = M.template leftCols<3>() * hat(X.t);
    out.template rightCols<3>().noalias() = (M_rho_hat_t + M.template rightCols<3>()) * R;
    return out;
  }
  template <int Rows>
  static Eigen::Matrix<double, Rows, 6> timesRightJacobian(const Eigen::Matrix<double, Rows, 6>& M,
                                                           const Vector6d& x) {
    const Eigen::Vector3d rho = x.head<3>();
    const Eigen::Vector3d phi = x.tail<3>();
    const Eigen::Matrix3d J = rightJacobianSO3(phi);
    const Eigen::Matrix3d Q = se3_detail::leftJacobianQ<double>(-rho, -phi);
    Eigen::Matrix<double, Rows, 6> out;
    out.template leftCols<3>().noalias() = M.template leftCols<3>() * J;
    out.template rightCols<3>().noalias() =
        M.template leftCols<3>() * Q + M.template rightCols<3>() * J;
    return out;
  }
  template <int Rows>
  static Eigen::Matrix<double, Rows, 6> timesRightJacobianInverse(
      const Eigen::Matrix<double, Rows, 6>& M, const Vector6d& x) {
    const Eigen::Vector3d rho = x.head<3>();
    const Eigen::Vector3d phi = x.tail<3>();
    const Eigen::Matrix3d J_inv = rightJacobianInverseSO3(phi);
    const Eigen::Matrix3d Q = se3_detail::leftJacobianQ<double>(-rho, -phi);
    // [K, (M_phi - K Q) J_inv] with K = M_rho J_inv.
    const Eigen::Matrix<double, Rows, 3> K = M.template leftCols<3>() * J_inv;
    Eigen::Matrix<double, Rows, 6> out;
    out.template leftCols<3>() = K;
    out.template rightCols<3>().noalias() = (M.template rightCols<3>() - K * Q) * J_inv;
    return out;
  }

  std::array<double, 4> b_, db_;  // Bt_j(u), dBt_j/du
  SE3d pose_;
  // Index j = 1..3 (entry 0 unused), as in the header comment.
  std::array<SE3d, 4> D_;         // T_{j-1}^-1 T_j
  std::array<Vector6d, 4> Omega_; // log(D_j)
  std::array<SE3d, 4> A_;         // exp(b_j Omega_j)
};

}  // namespace hsmap
