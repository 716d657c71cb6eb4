#pragma once
// GraphProblem: a FactorGraph and its Values handed to Ceres as one
// ceres::Problem.
//
// Variables. Every key touched by a factor becomes one parameter block that
// IS the Values' block (Values keeps block addresses stable), so the solver
// writes the optimum straight into the Values. Pose blocks (pose3) get the
// Se3Manifold (right perturbation T * exp(xi), xi = [rho; phi]); points,
// scalars and vectors are plain Euclidean blocks. Keys held in Values but not
// touched by any factor are left out of the problem (and unchanged).
//
// Factors. Each factor must be a CeresFactor (factors/ceres_factor.h); its
// raw residual is whitened by its NoiseModel (WhitenedCostFunction) and its
// RobustLoss becomes ceres::HuberLoss(scale) or ceres::CauchyLoss(scale) on
// the whitened residual, so scale is in sigmas: the cost of a factor is
// 0.5 rho(|R r|^2), with rho(s) = s inside the scale.
//
// Gauge. Visual factors alone (reprojections, between-pose factors) leave the
// problem invariant to a rigid motion of the whole scene (and, for a
// monocular problem, a scale): the Jacobian is rank deficient. The solver
// copes (Levenberg-Marquardt is damped) but the result drifts along the gauge
// and covariances are undefined. Fix it in one of two ways:
//   - hold variables constant: options.constant = {X(0)} for a pose, plus a
//     second pose or a landmark for a monocular scale;
//   - or let absolute factors fix it: INS position + attitude factors on the
//     keyframes (hsmap's normal case: the survey is geo-referenced through
//     them), or PosePriorFactor.
//
// Schur ordering. schurOrdering() puts landmarks (VariableKind::landmark)
// into the first elimination group so SPARSE_SCHUR, DENSE_SCHUR and
// ITERATIVE_SCHUR eliminate them and factor the reduced camera system
// (poses, spline, T_C_U, d). A Schur group must be an independent set (no factor between two of its
// members): a landmark that shares a factor with a landmark already in the
// group stays in the second group. Constant landmarks are not eliminated.
//
// Bounds. Optional box bounds on single stored doubles of non-pose variables
// (e.g. the time offset d within +-0.5 s), enforced by Ceres' projection.
//
// Constant keys that have a value but no factor are accepted and have no
// effect (e.g. "every spline control point" when some are not measured).
//
// Constant components (options.constant_components): single doubles of a
// vector or point held fixed by a ceres::SubsetManifold; errors when the
// key is a pose, not a variable, or an index is out of range.
//
// Errors (std::invalid_argument, thrown by the constructor): a factor's key
// without a value (the first few are listed), a factor that is not a
// CeresFactor, a cost-function block size or residual count that does not
// match the variable or the noise model, a constant key that is neither in
// the graph nor in the Values, a bound on a variable no factor uses, on a
// pose, or out of range.
//
// Lifetime: the problem keeps pointers into `values`; do not insert, erase or
// update variables while it exists.

#include <ceres/loss_function.h>
#include <ceres/manifold.h>
#include <ceres/ordered_groups.h>
#include <ceres/problem.h>

#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/graph/factor_graph.h"
#include "core/graph/key.h"
#include "core/graph/values.h"

namespace hsmap {

// lower <= values.data(key)[index] <= upper.
struct VariableBound {
  Key key;
  int index = 0;
  double lower = 0.0;
  double upper = 0.0;
};

struct GraphProblemOptions {
  // Variables held fixed at their current value (gauge, known calibration).
  std::set<Key> constant;
  // Single stored doubles of a non-pose variable held at their current value
  // while the rest of it is estimated (ceres::SubsetManifold), e.g. a
  // camera's distortion coefficient whose survey sigma is 0. The variable's
  // tangent space (and so its covariance) then has only the free components,
  // in stored order (GraphProblem::tangentSize()).
  std::map<Key, std::vector<int>> constant_components;
  std::vector<VariableBound> bounds;
};

// One factor at the current values.
struct FactorEvaluation {
  // |R r|: the norm of the whitened residual, in sigmas.
  double whitened_norm = 0.0;
  // 0.5 rho(|R r|^2): what the solver minimises.
  double cost = 0.0;
  // The factor has a robust loss and whitened_norm exceeds the loss scale:
  // the solver down-weights it as an outlier.
  bool beyond_loss_scale = false;
};

// Cost of the factors of one type at the current values.
struct FactorTypeCost {
  std::size_t count = 0;
  // sum of 0.5 rho(|R r|^2): what the solver minimises.
  double cost = 0.0;
  // Factors with a robust loss whose whitened residual norm exceeds the
  // loss scale (down-weighted as outliers).
  std::size_t beyond_loss_scale = 0;
};

class GraphProblem {
 public:
  GraphProblem(const FactorGraph& graph, Values& values, GraphProblemOptions options = {});
  ~GraphProblem();
  GraphProblem(const GraphProblem&) = delete;
  GraphProblem& operator=(const GraphProblem&) = delete;

  ceres::Problem& problem() { return *problem_; }
  const ceres::Problem& problem() const { return *problem_; }

  // Ceres's parameter block of `key`: the problem's own copy of the value,
  // held with every other in one buffer in key order. Ceres orders the
  // blocks of an elimination group by their addresses, and so the order of
  // the Schur complement's sums: with blocks scattered on the heap that
  // order (and the last bits of every solve) followed the allocator's
  // history, which another thread's frees can change from run to run. In
  // key order a solve gives the same bits in every run.
  double* block(Key key);
  const double* block(Key key) const;
  // Values -> the blocks (before Ceres reads them: solve, evaluation,
  // covariance) and the blocks -> Values (after a solve).
  void loadValues() const;
  void storeValues();
  const FactorGraph& graph() const { return graph_; }
  Values& values() { return values_; }
  const GraphProblemOptions& options() const { return options_; }

  // The variables of the problem, in key order.
  const std::vector<Key>& variables() const { return variables_; }
  bool isConstant(Key key) const { return options_.constant.count(key) != 0; }
  // The degrees of freedom of `key` in the solve: Values::tangentSize()
  // less its constant_components.
  int tangentSize(Key key) const;
  // Variables of the problem held constant (constant keys without factors
  // are not counted).
  std::size_t numConstantVariables() const { return num_constant_variables_; }
  // Degrees of freedom left to the solver (tangent sizes of non-constant variables).
  int numFreeParameters() const { return num_free_parameters_; }

  // A fresh ordering for Schur solvers (Ceres edits the ordering it is
  // given, so each solve needs its own): eliminable landmarks in group 0,
  // everything else in group 1. nullptr when no landmark can be eliminated
  // (Ceres then finds an independent set itself).
  std::shared_ptr<ceres::ParameterBlockOrdering> schurOrdering() const;
  std::size_t numEliminatedLandmarks() const { return eliminated_landmarks_.size(); }
  // The landmarks schurOrdering() puts in group 0 (free landmarks, no two
  // sharing a factor), in key order.
  const std::vector<Key>& eliminatedLandmarks() const { return eliminated_landmarks_; }

  // Every factor at the current values, in graph order: one evaluation of
  // all whitened residuals by Ceres with `num_threads` threads, the robust
  // loss applied here per factor. Throws std::runtime_error when a factor
  // cannot be evaluated. costByFactorType() and factorsBeyondLossScale()
  // (robust_outliers.h) are summaries of it.
  std::vector<FactorEvaluation> evaluateFactors(int num_threads = 1) const;
  // Cost per factor type (Factor::name()) at the current values.
  std::map<std::string, FactorTypeCost> costByFactorType(int num_threads = 1) const;

 private:
  const FactorGraph& graph_;
  Values& values_;
  GraphProblemOptions options_;
  // Owned here and shared by the problem's blocks, so they are declared
  // before (and destroyed after) the problem.
  std::unique_ptr<ceres::Manifold> se3_manifold_;
  std::map<Key, std::unique_ptr<ceres::Manifold>> subset_manifolds_;
  std::map<std::pair<int, double>, std::unique_ptr<ceres::LossFunction>> losses_;
  std::unique_ptr<ceres::Problem> problem_;

  std::vector<Key> variables_;
  mutable std::vector<double> blocks_;        // every variable's value, in key order
  std::map<Key, std::size_t> block_offset_;  // where each starts in blocks_
  std::vector<Key> eliminated_landmarks_;
  std::vector<ceres::ResidualBlockId> residual_blocks_;    // by factor index
  std::vector<const ceres::LossFunction*> factor_losses_;  // by factor index (nullptr: none)
  int num_free_parameters_ = 0;
  std::size_t num_constant_variables_ = 0;
};

}  // namespace hsmap
