#pragma once
// SolverOptions: how a factor graph is optimised. Always Levenberg-Marquardt
// (Ceres' trust-region minimiser); the preset chooses how each step's linear
// system is solved:
//
//   sparse_schur (default)  Schur complement over the landmarks, then a sparse
//                           Cholesky of the reduced camera system (SuiteSparse
//                           CHOLMOD). Exact; the right choice for bundle
//                           adjustment up to a few thousand poses / spline
//                           control points.
//   iterative_schur         Same elimination, then conjugate gradients on the
//                           reduced system with the SCHUR_JACOBI
//                           preconditioner. Less memory, inexact steps; for
//                           very large problems where the reduced system's
//                           factor no longer fits.
//   sparse_normal_cholesky  Sparse Cholesky of the full normal equations
//                           J^T J (SuiteSparse). For problems without
//                           landmarks (spline fits, pose graphs).
//   dense_schur             Same elimination as sparse_schur, then a dense
//                           Cholesky (Eigen) of the reduced camera system.
//                           For the small windows of a local (sliding-window)
//                           bundle adjustment: a few to a few tens of free
//                           keyframes that share most landmarks, so the
//                           reduced system is small and nearly full: a
//                           dense factor of it is as fast as CHOLMOD's (the
//                           same time on an 8-keyframe window) without the
//                           sparse machinery. Its cost grows with the cube
//                           of the free pose count (6 per keyframe), so
//                           beyond roughly a hundred keyframes (Ceres'
//                           advice) use sparse_schur.
//
// Every field has the default shown and validate() says what is wrong with a
// field (std::invalid_argument naming it, the value and what is allowed).

#include <ceres/solver.h>

#include <iosfwd>
#include <string>

namespace hsmap {

struct SolverOptions {
  // The values are stable (benchmarks pass them as integers): append new presets.
  enum class LinearSolver { sparse_schur, iterative_schur, sparse_normal_cholesky, dense_schur };

  LinearSolver linear_solver = LinearSolver::sparse_schur;
  // Upper bound on Levenberg-Marquardt iterations (successful + rejected steps).
  int max_iterations = 100;
  // Stop when |cost change| / cost < function_tolerance.
  double function_tolerance = 1e-6;
  // Stop when the max-norm of the projected gradient < gradient_tolerance.
  double gradient_tolerance = 1e-10;
  // Stop when |step| < parameter_tolerance * (|x| + parameter_tolerance).
  double parameter_tolerance = 1e-8;
  // Wall-clock budget of one solve, in seconds.
  double max_time_s = 1e6;
  // Threads for Jacobian evaluation and the linear solver; 0 means every
  // hardware thread (std::thread::hardware_concurrency()).
  int num_threads = 0;
  // One line per iteration on progress_stream (std::cerr when null): cost,
  // relative decrease, trust-region radius, elapsed time.
  bool verbose = false;
  std::ostream* progress_stream = nullptr;

  // Throws std::invalid_argument for a non-positive iteration count, time,
  // a negative thread count or a tolerance that is not a finite number >= 0.
  void validate() const;
  // num_threads with 0 resolved to the hardware thread count (>= 1).
  int resolvedNumThreads() const;
  // The matching ceres::Solver::Options (without the elimination ordering,
  // which depends on the problem: see GraphProblem::schurOrdering()).
  ceres::Solver::Options toCeres() const;
};

// "sparse_schur", "iterative_schur", "sparse_normal_cholesky", "dense_schur".
const char* toString(SolverOptions::LinearSolver solver);
// Inverse of toString; throws std::invalid_argument listing the valid names.
SolverOptions::LinearSolver parseLinearSolver(const std::string& name);

}  // namespace hsmap
