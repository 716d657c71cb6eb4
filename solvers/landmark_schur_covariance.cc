#include "solvers/landmark_schur_covariance.h"

#include "core/util/thread_budget.h"

#include <ceres/crs_matrix.h>
#include <ceres/problem.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace hsmap::internal {

namespace {

using SparseColumns = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

constexpr int kLandmarkSize = 3;

const char* const kPrefix = "marginal covariance (landmark_schur): ";

// Columns of the (Jacobi-scaled) selector R for one requested key, so that
// the covariance block of keys a, b is R_a^T S'^-1 R_b (+ H_ll^-1 when a = b
// is an eliminated landmark): `values` (rows.size() x tangent) on the reduced
// degrees of freedom `rows`.
struct KeyColumns {
  int tangent = 0;
  bool constant = false;
  std::vector<int> rows;
  Eigen::MatrixXd values;
  // Eliminated landmark: its block of H_ll^-1; empty otherwise.
  Eigen::Matrix3d landmark_inverse = Eigen::Matrix3d::Zero();
  bool is_landmark = false;
  // First column of the key in the batch of solved columns (solve path).
  int first_column = 0;
};

// The reduced system, factored, and the columns of the requested keys.
class LandmarkSchur {
 public:
  LandmarkSchur(GraphProblem& problem, const std::vector<Key>& keys,
                const CovarianceOptions& options);

  // Covariance block of keys[a] and keys[b].
  Eigen::MatrixXd block(std::size_t a, std::size_t b) const;

 private:
  void evaluateAndReduce(GraphProblem& problem, const CovarianceOptions& options);
  void factor(const GraphProblem& problem, const CovarianceOptions& options);
  void solveColumns();

  // Free variables in Jacobian column order: reduced first, then eliminated.
  std::vector<Key> reduced_;
  std::unordered_map<Key, int> reduced_offset_;
  int reduced_dimension_ = 0;
  std::vector<Key> landmarks_;
  std::unordered_map<Key, int> landmark_index_;

  std::vector<Key> keys_;
  std::vector<KeyColumns> columns_;
  // Requested eliminated landmarks: index into landmarks_ -> index into keys_.
  std::unordered_map<int, std::size_t> requested_landmarks_;

  // S, then (in place) the Cholesky factor of the Jacobi-scaled S.
  Eigen::MatrixXd S_;
  Eigen::VectorXd scale_;  // S' = diag(scale) S diag(scale)
  // Either S'^-1 (many columns asked for) or S'^-1 R for the batch of all
  // requested columns.
  Eigen::MatrixXd inverse_;
  bool full_inverse_ = false;
};

LandmarkSchur::LandmarkSchur(GraphProblem& problem, const std::vector<Key>& keys,
                             const CovarianceOptions& options)
    : keys_(keys) {
  const std::unordered_set<Key> eliminated(problem.eliminatedLandmarks().begin(),
                                           problem.eliminatedLandmarks().end());
  for (const Key& key : problem.variables()) {
    if (problem.isConstant(key) || eliminated.count(key) != 0) continue;
    reduced_offset_.emplace(key, reduced_dimension_);
    reduced_.push_back(key);
    reduced_dimension_ += problem.tangentSize(key);
  }
  if (reduced_dimension_ > kLandmarkSchurMaxReducedDimension) {
    throw std::invalid_argument(
        std::string(kPrefix) + "the reduced system has " + std::to_string(reduced_dimension_) +
        " degrees of freedom (the free variables other than the " +
        std::to_string(problem.eliminatedLandmarks().size()) +
        " eliminated landmarks), more than the " +
        std::to_string(kLandmarkSchurMaxReducedDimension) +
        " this dense method handles; use the sparse_qr algorithm");
  }
  for (const Key& key : problem.eliminatedLandmarks()) {
    if (problem.tangentSize(key) != kLandmarkSize) {
      throw std::runtime_error(std::string(kPrefix) + "eliminated landmark " + key.toString() +
                               " has " + std::to_string(problem.tangentSize(key)) +
                               " degrees of freedom, not 3");
    }
    landmark_index_.emplace(key, static_cast<int>(landmarks_.size()));
    landmarks_.push_back(key);
  }

  columns_.resize(keys_.size());
  for (std::size_t a = 0; a < keys_.size(); ++a) {
    KeyColumns& columns = columns_[a];
    columns.tangent = problem.tangentSize(keys_[a]);
    columns.constant = problem.isConstant(keys_[a]);
    if (columns.constant) continue;
    const auto landmark = landmark_index_.find(keys_[a]);
    if (landmark != landmark_index_.end()) {
      columns.is_landmark = true;
      requested_landmarks_.emplace(landmark->second, a);
    } else {
      const int offset = reduced_offset_.at(keys_[a]);
      for (int i = 0; i < columns.tangent; ++i) columns.rows.push_back(offset + i);
      columns.values = Eigen::MatrixXd::Identity(columns.tangent, columns.tangent);
    }
  }

  if (reduced_dimension_ == 0 && landmarks_.empty()) return;  // every variable constant
  evaluateAndReduce(problem, options);
  factor(problem, options);
  // R' = diag(scale) R.
  for (KeyColumns& columns : columns_) {
    for (std::size_t i = 0; i < columns.rows.size(); ++i) {
      columns.values.row(static_cast<Eigen::Index>(i)) *= scale_[columns.rows[i]];
    }
  }
  solveColumns();
}

void LandmarkSchur::evaluateAndReduce(GraphProblem& problem, const CovarianceOptions& options) {
  const int n_c = reduced_dimension_;
  const int n_l = kLandmarkSize * static_cast<int>(landmarks_.size());

  // J over [reduced | eliminated landmarks], tangent-space columns (Ceres
  // applies the manifolds), whitened and robustified as in the solve.
  ceres::Problem::EvaluateOptions evaluate_options;
  problem.loadValues();
  for (const Key& key : reduced_) evaluate_options.parameter_blocks.push_back(problem.block(key));
  for (const Key& key : landmarks_) evaluate_options.parameter_blocks.push_back(problem.block(key));
  evaluate_options.apply_loss_function = options.apply_loss_function;
  int threads = options.num_threads;
  if (threads <= 0) threads = threadBudget();
  evaluate_options.num_threads = threads;
  // J is evaluated a pass of residual blocks at a time and reduced into
  // H_cc (dense: it becomes S), the landmarks' 3x3 blocks of H_ll and the
  // sparse H_lc, so memory holds one pass's Jacobian rather than the whole
  // (on a 100 m survey's joint problem, 3 M reprojections, the whole
  // Jacobian and its products took several GB).
  std::vector<ceres::ResidualBlockId> residual_blocks;
  problem.problem().GetResidualBlocks(&residual_blocks);
  const std::size_t per_pass = std::max<std::size_t>(1, options.residual_blocks_per_pass);
  S_ = Eigen::MatrixXd::Zero(n_c, n_c);
  std::vector<Eigen::Matrix3d> blocks(landmarks_.size(), Eigen::Matrix3d::Zero());
  SparseRows H_lc(n_l, n_c);
  for (std::size_t begin = 0; begin < residual_blocks.size(); begin += per_pass) {
    const std::size_t end = std::min(residual_blocks.size(), begin + per_pass);
    evaluate_options.residual_blocks.assign(residual_blocks.begin() + std::ptrdiff_t(begin),
                                            residual_blocks.begin() + std::ptrdiff_t(end));
    SparseColumns J;
    {
      ceres::CRSMatrix crs;
      if (!problem.problem().Evaluate(evaluate_options, nullptr, nullptr, nullptr, &crs)) {
        throw std::runtime_error(std::string(kPrefix) +
                                 "a factor failed to evaluate at the current values");
      }
      if (crs.num_cols != n_c + n_l) {
        throw std::runtime_error(std::string(kPrefix) + "Ceres returned a Jacobian of " +
                                 std::to_string(crs.num_cols) + " columns for " +
                                 std::to_string(n_c + n_l) + " free degrees of freedom");
      }
      const Eigen::Map<const SparseRows> rows(crs.num_rows, crs.num_cols,
                                              static_cast<Eigen::Index>(crs.values.size()),
                                              crs.rows.data(), crs.cols.data(), crs.values.data());
      J = rows;  // column-major copy, rows sorted within each column
    }
    // Column blocks of J (views, no copies).
    const auto J_c = J.leftCols(n_c);
    const auto J_l = J.rightCols(n_l);
    const SparseColumns H_cc = J_c.transpose() * J_c;
    for (int column = 0; column < H_cc.outerSize(); ++column) {
      for (SparseColumns::InnerIterator it(H_cc, column); it; ++it) {
        S_(it.row(), column) += it.value();
      }
    }
    // Landmark blocks of H_ll (and a check that they are the only blocks).
    const SparseColumns H_ll = J_l.transpose() * J_l;
    for (int column = 0; column < H_ll.outerSize(); ++column) {
      for (SparseColumns::InnerIterator it(H_ll, column); it; ++it) {
        const int row = static_cast<int>(it.row());
        if (row / kLandmarkSize != column / kLandmarkSize) {
          if (it.value() == 0.0) continue;
          throw std::runtime_error(std::string(kPrefix) + "a residual touches both " +
                                   landmarks_[row / kLandmarkSize].toString() + " and " +
                                   landmarks_[column / kLandmarkSize].toString() +
                                   ", which are both eliminated");
        }
        blocks[column / kLandmarkSize](row % kLandmarkSize, column % kLandmarkSize) += it.value();
      }
    }
    H_lc += SparseRows(J_l.transpose() * J_c);
  }

  // S = H_cc - sum over landmarks of B^T C^-1 B, B = the landmark's 3 rows
  // of H_lc restricted to the k reduced columns they touch.
  std::vector<int> position(static_cast<std::size_t>(n_c), -1);
  std::vector<int> touched;
  Eigen::Matrix<double, kLandmarkSize, Eigen::Dynamic> B;
  for (std::size_t l = 0; l < landmarks_.size(); ++l) {
    const Eigen::Matrix3d& C = blocks[l];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(C, Eigen::EigenvaluesOnly);
    const double largest = eigen.eigenvalues()(2);
    const double smallest = eigen.eigenvalues()(0);
    if (!(std::isfinite(largest) && largest > 0.0 &&
          smallest >= options.min_reciprocal_condition_number * largest)) {
      rankDeficient(problem);
    }
    const Eigen::Matrix3d solved = C.llt().solve(Eigen::Matrix3d::Identity());
    const Eigen::Matrix3d C_inverse = 0.5 * (solved + solved.transpose());

    touched.clear();
    for (int i = 0; i < kLandmarkSize; ++i) {
      for (SparseRows::InnerIterator it(H_lc, kLandmarkSize * static_cast<int>(l) + i); it; ++it) {
        const int column = static_cast<int>(it.col());
        if (position[column] < 0) {
          position[column] = static_cast<int>(touched.size());
          touched.push_back(column);
        }
      }
    }
    const int k = static_cast<int>(touched.size());
    B.setZero(kLandmarkSize, k);
    for (int i = 0; i < kLandmarkSize; ++i) {
      for (SparseRows::InnerIterator it(H_lc, kLandmarkSize * static_cast<int>(l) + i); it; ++it) {
        B(i, position[it.col()]) = it.value();
      }
    }
    const Eigen::MatrixXd W = B.transpose() * C_inverse;  // k x 3: this landmark's rows of H_cl H_ll^-1
    const Eigen::MatrixXd update = W * B;                 // k x k
    for (int b = 0; b < k; ++b) {
      for (int a = 0; a < k; ++a) S_(touched[a], touched[b]) -= update(a, b);
    }

    const auto requested = requested_landmarks_.find(static_cast<int>(l));
    if (requested != requested_landmarks_.end()) {
      KeyColumns& columns = columns_[requested->second];
      columns.rows = touched;
      columns.values = -W;
      columns.landmark_inverse = C_inverse;
    }
    for (const int column : touched) position[column] = -1;
  }
}

void LandmarkSchur::factor(const GraphProblem& problem, const CovarianceOptions& options) {
  const int n_c = reduced_dimension_;
  scale_.resize(n_c);
  for (int i = 0; i < n_c; ++i) {
    const double diagonal = S_(i, i);
    if (!(std::isfinite(diagonal) && diagonal > 0.0)) rankDeficient(problem);
    scale_[i] = 1.0 / std::sqrt(diagonal);
  }
  if (n_c == 0) return;
  S_.array().colwise() *= scale_.array();
  S_.array().rowwise() *= scale_.transpose().array();
  // The lower triangle only (the upper one is the rounded copy).
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>, Eigen::Lower> llt(S_);
  if (llt.info() != Eigen::Success) rankDeficient(problem);
  const double rcond = llt.rcond();
  if (!(rcond >= options.min_reciprocal_condition_number)) rankDeficient(problem);
}

void LandmarkSchur::solveColumns() {
  const int n_c = reduced_dimension_;
  if (n_c == 0) return;
  int num_columns = 0;
  for (KeyColumns& columns : columns_) {
    columns.first_column = num_columns;
    if (!columns.constant) num_columns += columns.tangent;
  }
  // S'^-1 X = L^-T L^-1 X, L in the lower triangle of S_.
  auto solveInPlace = [&](Eigen::MatrixXd& X) {
    S_.triangularView<Eigen::Lower>().solveInPlace(X);
    S_.adjoint().triangularView<Eigen::Upper>().solveInPlace(X);
  };
  if (num_columns >= n_c / 2) {
    // Asked for about as many columns as S has: invert it once, then every
    // block is a small gather.
    full_inverse_ = true;
    inverse_ = Eigen::MatrixXd::Identity(n_c, n_c);
    solveInPlace(inverse_);
  } else {
    inverse_ = Eigen::MatrixXd::Zero(n_c, num_columns);
    for (const KeyColumns& columns : columns_) {
      if (columns.constant) continue;
      for (std::size_t i = 0; i < columns.rows.size(); ++i) {
        inverse_.block(columns.rows[i], columns.first_column, 1, columns.tangent) =
            columns.values.row(static_cast<Eigen::Index>(i));
      }
    }
    solveInPlace(inverse_);
  }
}

Eigen::MatrixXd LandmarkSchur::block(std::size_t a, std::size_t b) const {
  const KeyColumns& A = columns_[a];
  const KeyColumns& Bc = columns_[b];
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(A.tangent, Bc.tangent);
  if (A.constant || Bc.constant) return result;
  if (!A.rows.empty() && !Bc.rows.empty()) {
    Eigen::MatrixXd gathered(A.rows.size(), Bc.tangent);
    if (full_inverse_) {
      // S'^-1 (A.rows, B.rows) R'_b
      Eigen::MatrixXd sub(A.rows.size(), Bc.rows.size());
      for (std::size_t j = 0; j < Bc.rows.size(); ++j) {
        for (std::size_t i = 0; i < A.rows.size(); ++i) sub(i, j) = inverse_(A.rows[i], Bc.rows[j]);
      }
      gathered = sub * Bc.values;
    } else {
      for (std::size_t i = 0; i < A.rows.size(); ++i) {
        gathered.row(static_cast<Eigen::Index>(i)) =
            inverse_.block(A.rows[i], Bc.first_column, 1, Bc.tangent);
      }
    }
    result = A.values.transpose() * gathered;
  }
  if (a == b && A.is_landmark) result += A.landmark_inverse;
  return result;
}

}  // namespace

std::map<Key, Eigen::MatrixXd> landmarkSchurMarginalCovariances(GraphProblem& problem,
                                                                const std::vector<Key>& keys,
                                                                const CovarianceOptions& options) {
  const LandmarkSchur schur(problem, keys, options);
  std::map<Key, Eigen::MatrixXd> result;
  for (std::size_t a = 0; a < keys.size(); ++a) {
    const Eigen::MatrixXd block = schur.block(a, a);
    // Exactly symmetric, as a covariance should be.
    result.emplace(keys[a], 0.5 * (block + block.transpose()));
  }
  return result;
}

Eigen::MatrixXd landmarkSchurJointCovariance(GraphProblem& problem, const std::vector<Key>& keys,
                                             const CovarianceOptions& options) {
  const LandmarkSchur schur(problem, keys, options);
  std::vector<int> offsets;
  int n = 0;
  for (const Key& key : keys) {
    offsets.push_back(n);
    n += problem.tangentSize(key);
  }
  Eigen::MatrixXd joint(n, n);
  for (std::size_t a = 0; a < keys.size(); ++a) {
    for (std::size_t b = a; b < keys.size(); ++b) {
      const Eigen::MatrixXd block = schur.block(a, b);
      joint.block(offsets[a], offsets[b], block.rows(), block.cols()) = block;
      joint.block(offsets[b], offsets[a], block.cols(), block.rows()) = block.transpose();
    }
  }
  return 0.5 * (joint + joint.transpose());
}

}  // namespace hsmap::internal
