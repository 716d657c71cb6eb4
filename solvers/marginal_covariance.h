#pragma once
// Marginal covariances of chosen variables at the current estimate, through
// ceres::Covariance.
//
// Under the Gauss-Newton approximation the covariance of all free variables
// is (J^T J)^-1, J the Jacobian of the whitened (and, by default, robustified)
// residuals in the TANGENT space of each variable. The marginal covariance of
// a variable is its diagonal block of that inverse (not the inverse of its
// own block of J^T J, which would ignore the correlations), and the joint
// covariance of a few variables is the matching sub-matrix. Units and order:
//   pose3   6x6 over the right perturbation xi = [rho; phi] of
//           Se3Manifold (metres, radians; expressed in the pose's own frame,
//           e.g. the body frame of T_W_B)
//   point3  3x3 (metres^2), scalar 1x1, vector n x n (stored units; only
//           the free ones, in stored order, when GraphProblemOptions::
//           constant_components holds some)
// A variable held constant has a zero covariance (and zero correlations).
//
// Rank deficiency. When J does not have full column rank the covariance is
// undefined, almost always because the gauge is free (a graph with only
// relative factors). The computation then throws CovarianceRankDeficient
// telling the user to hold a pose constant or add absolute (INS / prior)
// factors; see graph_problem.h, "Gauge".
//
// Cost: sparse QR (SuiteSparseQR) of the whole Jacobian, dominated by the
// Jacobian's size, whatever few variables are asked for. dense_svd is only
// for small problems (it forms the dense J^T J). landmark_schur eliminates
// the landmarks (3x3 blocks) and factors only the dense reduced system of
// the other variables: for bundle adjustment with many landmarks and a few
// thousand other degrees of freedom at most it is much faster and lighter
// than sparse_qr (solvers/landmark_schur_covariance.h).

#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/graph/key.h"
#include "solvers/graph_problem.h"

namespace hsmap {

struct CovarianceOptions {
  // sparse_qr, dense_svd: ceres::Covariance (SPARSE_QR with SuiteSparse,
  // DENSE_SVD). landmark_schur: Schur complement on the eliminated landmarks
  // and a dense Cholesky of the reduced system (landmark_schur_covariance.h;
  // at most 20 000 reduced degrees of freedom).
  enum class Algorithm { sparse_qr, dense_svd, landmark_schur };
  Algorithm algorithm = Algorithm::sparse_qr;
  // 0 means every hardware thread.
  int num_threads = 0;
  // Whether robust losses reweight the residuals, as in the solve.
  bool apply_loss_function = true;
  // dense_svd: the problem counts as rank deficient when the ratio of the
  // smallest to the largest eigenvalue of J^T J is below this.
  // landmark_schur: the same threshold on each landmark's 3x3 block of J^T J
  // (eigenvalue ratio) and on the reciprocal condition estimate of the
  // Jacobi-scaled reduced system.
  double min_reciprocal_condition_number = 1e-14;
  // landmark_schur: the Jacobian is evaluated and reduced this many residual
  // blocks at a time (memory: about 1.3 kB per reprojection-sized block in a
  // pass, instead of the whole Jacobian and its products at once).
  std::size_t residual_blocks_per_pass = 100000;
};

// Thrown when the Jacobian is rank deficient (e.g. free gauge).
class CovarianceRankDeficient : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Marginal covariance of each key (tangent space; see the header comment).
// Throws std::invalid_argument for a key that is not a variable of the
// problem, CovarianceRankDeficient when the covariance is undefined.
std::map<Key, Eigen::MatrixXd> marginalCovariances(GraphProblem& problem,
                                                   const std::vector<Key>& keys,
                                                   const CovarianceOptions& options = {});

// Joint covariance of the keys, stacked in the given order (sum of their
// tangent sizes, square). Same errors as marginalCovariances().
Eigen::MatrixXd jointMarginalCovariance(GraphProblem& problem, const std::vector<Key>& keys,
                                        const CovarianceOptions& options = {});

}  // namespace hsmap
