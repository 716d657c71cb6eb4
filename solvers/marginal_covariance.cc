#include "solvers/marginal_covariance.h"

#include "core/util/thread_budget.h"

#include <ceres/covariance.h>

#include <algorithm>
#include <set>
#include <thread>
#include <utility>

#include "solvers/landmark_schur_covariance.h"

namespace hsmap {

namespace internal {

[[noreturn]] void rankDeficient(const GraphProblem& problem) {
  throw CovarianceRankDeficient(
      "marginal covariance: the problem is rank deficient (its Jacobian does not have full "
      "column rank over the " +
      std::to_string(problem.numFreeParameters()) +
      " free degrees of freedom), so the covariance is undefined. The usual cause is a free "
      "gauge: hold one pose constant (e.g. constant = {X(0)}) or add absolute factors (INS "
      "position/attitude, pose priors) that fix the world frame; a monocular problem also "
      "needs its scale fixed");
}

}  // namespace internal

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void checkKeys(const GraphProblem& problem, const std::vector<Key>& keys) {
  if (keys.empty()) throw std::invalid_argument("marginal covariance: no variables were asked for");
  std::set<Key> seen;
  const std::vector<Key>& variables = problem.variables();
  for (const Key& key : keys) {
    if (!std::binary_search(variables.begin(), variables.end(), key)) {
      throw std::invalid_argument("marginal covariance: " + key.toString() +
                                  " is not a variable of the problem (no factor uses it)");
    }
    if (!seen.insert(key).second) {
      throw std::invalid_argument("marginal covariance: " + key.toString() +
                                  " is asked for twice");
    }
  }
}

ceres::Covariance::Options ceresOptions(const CovarianceOptions& options) {
  ceres::Covariance::Options ceres_options;
  ceres_options.algorithm_type = options.algorithm == CovarianceOptions::Algorithm::sparse_qr
                                     ? ceres::SPARSE_QR
                                     : ceres::DENSE_SVD;
  ceres_options.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  ceres_options.min_reciprocal_condition_number = options.min_reciprocal_condition_number;
  // Rank deficiency is an error (null_space_rank = 0), never a silently
  // truncated pseudo-inverse.
  ceres_options.null_space_rank = 0;
  ceres_options.apply_loss_function = options.apply_loss_function;
  int threads = options.num_threads;
  if (threads <= 0) threads = threadBudget();
  ceres_options.num_threads = threads;
  return ceres_options;
}

using internal::rankDeficient;

// Fewer residuals than degrees of freedom is rank deficient whatever the
// values. Ceres' DENSE_SVD misses this case: its thin SVD of a wide Jacobian
// has only as many singular values as rows, all of which may be fine.
void checkResidualCount(GraphProblem& problem) {
  if (problem.problem().NumResiduals() < problem.numFreeParameters()) rankDeficient(problem);
}

}  // namespace

std::map<Key, Eigen::MatrixXd> marginalCovariances(GraphProblem& problem,
                                                   const std::vector<Key>& keys,
                                                   const CovarianceOptions& options) {
  checkKeys(problem, keys);
  checkResidualCount(problem);
  if (options.algorithm == CovarianceOptions::Algorithm::landmark_schur) {
    return internal::landmarkSchurMarginalCovariances(problem, keys, options);
  }
  problem.loadValues();
  std::vector<std::pair<const double*, const double*>> pairs;
  for (const Key& key : keys) pairs.emplace_back(problem.block(key), problem.block(key));
  ceres::Covariance covariance(ceresOptions(options));
  if (!covariance.Compute(pairs, &problem.problem())) rankDeficient(problem);

  std::map<Key, Eigen::MatrixXd> result;
  for (const Key& key : keys) {
    const int n = problem.tangentSize(key);
    RowMajorMatrix block(n, n);
    if (!covariance.GetCovarianceBlockInTangentSpace(problem.block(key), problem.block(key),
                                                     block.data())) {
      throw std::runtime_error("marginal covariance: Ceres did not return the block of " +
                               key.toString());
    }
    result.emplace(key, Eigen::MatrixXd(block));
  }
  return result;
}

Eigen::MatrixXd jointMarginalCovariance(GraphProblem& problem, const std::vector<Key>& keys,
                                        const CovarianceOptions& options) {
  checkKeys(problem, keys);
  checkResidualCount(problem);
  if (options.algorithm == CovarianceOptions::Algorithm::landmark_schur) {
    return internal::landmarkSchurJointCovariance(problem, keys, options);
  }
  problem.loadValues();
  std::vector<const double*> blocks;
  int n = 0;
  for (const Key& key : keys) {
    blocks.push_back(problem.block(key));
    n += problem.tangentSize(key);
  }
  ceres::Covariance covariance(ceresOptions(options));
  if (!covariance.Compute(blocks, &problem.problem())) rankDeficient(problem);
  RowMajorMatrix joint(n, n);
  if (!covariance.GetCovarianceMatrixInTangentSpace(blocks, joint.data())) {
    throw std::runtime_error("marginal covariance: Ceres did not return the joint covariance");
  }
  return Eigen::MatrixXd(joint);
}

}  // namespace hsmap
