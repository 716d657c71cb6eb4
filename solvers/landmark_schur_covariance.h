#pragma once
// Marginal covariances by landmark elimination (CovarianceOptions::Algorithm::
// landmark_schur). Internal to solvers/marginal_covariance.cc, which checks
// the keys and dispatches here; use marginalCovariances() /
// jointMarginalCovariance() rather than these functions.
//
// What it computes. The same Gauss-Newton covariance as the other algorithms
// (marginal_covariance.h): the requested blocks of (J^T J)^-1, J the Jacobian
// of the whitened (and, with options.apply_loss_function, robustified)
// residuals in the TANGENT space of every free variable, with the same units
// and order:
//   pose3   6x6 over the right perturbation xi = [rho; phi] of Se3Manifold
//           (metres, radians; in the pose's own frame)
//   point3  3x3 (metres^2), scalar 1x1, vector n x n (stored units)
// and zero blocks (and correlations) for variables held constant.
//
// How. J comes from ceres::Problem::Evaluate() over the free blocks, a pass
// of options.residual_blocks_per_pass residual blocks at a time, each pass
// reduced into H_cc, H_ll and H_lc below before the next, with columns
// ordered [c | l]: c the reduced variables (poses, spline control points,
// extrinsics, time offsets, intrinsics and the landmarks GraphProblem cannot
// eliminate), l the landmarks GraphProblem::eliminatedLandmarks() (the Schur
// group of the solver; no two share a factor). Ceres returns the columns of
// a block with a Manifold in its tangent space already (Problem::Evaluate,
// problem.h "Note 2": a block contributes TangentSize() columns; the
// evaluator multiplies by the manifold's PlusJacobian), and the robust loss
// is applied the way the solver and ceres::Covariance apply it (Ceres'
// Corrector: sqrt(rho') times a rank-one correction of the whitened
// Jacobian). Then, with H = J^T J = [H_cc H_cl; H_lc H_ll]:
//   H_ll is block diagonal with 3x3 blocks (every residual touches at most
//   one eliminated landmark), inverted block by block;
//   S = H_cc - H_cl H_ll^-1 H_lc, the reduced camera system, formed DENSE
//   landmark by landmark, Jacobi-scaled and factored by Cholesky (LLT);
//   cov(c, c) = S^-1,  cov(c, l) = -S^-1 W,  cov(l, l) = H_ll^-1 + W^T S^-1 W,
//   W = H_cl H_ll^-1 (sparse: a landmark only couples to the variables of
//   its own factors).
// Requested landmarks are therefore supported too (their block and their
// correlations with everything else requested), at a cost of a few k x k
// products each (k: the reduced degrees of freedom the landmark's factors
// touch).
//
// Why. Only the reduced system is dense: memory is one pass's Jacobian (CRS,
// about 12 bytes per non-zero, held twice while it is converted), the sparse
// H_lc (the landmarks' couplings) plus n_c^2 doubles
// for S (and n_c^2 more for S^-1 when a marginal call asks for as many
// columns as S has), time is one Jacobian evaluation, the sparse products,
// sum over landmarks of k^2 and n_c^3 / 3 for the Cholesky. For a survey
// with ~1500 reduced and ~30 000 landmark degrees of freedom that is seconds
// and well under a few GB, where a sparse QR of the whole Jacobian takes
// minutes and many GB.
//
// When it applies. Problems whose reduced dimension n_c is at most
// kLandmarkSchurMaxReducedDimension (S is dense); otherwise
// std::invalid_argument (use sparse_qr). Without eliminated landmarks it is a
// plain dense Cholesky of J^T J.
//
// Rank deficiency (CovarianceRankDeficient, the same message as the other
// algorithms): a landmark block of H_ll whose smallest to largest eigenvalue
// ratio is below options.min_reciprocal_condition_number (or not positive),
// a reduced degree of freedom with no information (zero diagonal of S), a
// Cholesky failure of the Jacobi-scaled S (not positive definite), or its
// reciprocal condition number estimate (Eigen's LLT::rcond(), 1-norm) below
// options.min_reciprocal_condition_number. The check is on the Jacobi-scaled
// S, so it does not depend on the units of the variables.
//
// Errors besides: std::runtime_error when a factor cannot be evaluated, or
// when a residual touches two eliminated landmarks (GraphProblem never
// builds such an elimination set; this would be an internal error).

#include <Eigen/Core>
#include <map>
#include <vector>

#include "core/graph/key.h"
#include "solvers/graph_problem.h"
#include "solvers/marginal_covariance.h"

namespace hsmap::internal {

// Largest reduced dimension n_c (S is n_c x n_c dense: 20 000 is 3.2 GB).
constexpr int kLandmarkSchurMaxReducedDimension = 20000;

// The keys have been checked by the caller (variables of the problem, no
// repeats, enough residuals). Same results as marginalCovariances() /
// jointMarginalCovariance() (marginal_covariance.h).
std::map<Key, Eigen::MatrixXd> landmarkSchurMarginalCovariances(GraphProblem& problem,
                                                                const std::vector<Key>& keys,
                                                                const CovarianceOptions& options);
Eigen::MatrixXd landmarkSchurJointCovariance(GraphProblem& problem, const std::vector<Key>& keys,
                                             const CovarianceOptions& options);

// Throws the CovarianceRankDeficient of every algorithm (defined in
// marginal_covariance.cc).
[[noreturn]] void rankDeficient(const GraphProblem& problem);

}  // namespace hsmap::internal
