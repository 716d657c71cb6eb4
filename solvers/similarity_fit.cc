#include "solvers/similarity_fit.h"

#include <ceres/ceres.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// x = (log s, theta (3), tau (3)); R = exp(theta) R0.
constexpr int kUnknowns = 7;

template <typename T>
Eigen::Quaternion<T> rotationOf(const T* x, const Eigen::Quaterniond& R0) {
  const Eigen::Matrix<T, 3, 1> theta(x[1], x[2], x[3]);
  return expSO3(theta) * R0.cast<T>();
}

// W (p_T - (s R (p_S - c) + tau + R l_S)).
struct PositionResidual {
  Eigen::Vector3d p_centred;  // p_S - c
  Eigen::Vector3d lever;
  Eigen::Vector3d p_target;
  Eigen::Vector3d inverse_sigma;
  Eigen::Quaterniond R0;

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const Eigen::Quaternion<T> R = rotationOf(x, R0);
    const Eigen::Matrix<T, 3, 1> tau(x[4], x[5], x[6]);
    const Eigen::Matrix<T, 3, 1> predicted =
        ceres::exp(x[0]) * (R * p_centred.cast<T>()) + tau + R * lever.cast<T>();
    for (int i = 0; i < 3; ++i) residual[i] = (T(p_target[i]) - predicted[i]) * inverse_sigma[i];
    return true;
  }
};

// A log(q_T^-1 R q_S), on the body's axes.
struct AttitudeResidual {
  Eigen::Quaterniond q_target_inverse;
  Eigen::Quaterniond q_source;
  Eigen::Vector3d inverse_sigma;
  Eigen::Quaterniond R0;

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const Eigen::Quaternion<T> error =
        q_target_inverse.cast<T>() * (rotationOf(x, R0) * q_source.cast<T>());
    const Eigen::Matrix<T, 3, 1> phi = logSO3(error);
    for (int i = 0; i < 3; ++i) residual[i] = phi[i] * inverse_sigma[i];
    return true;
  }
};

Eigen::Vector3d inverseOf(const Eigen::Vector3d& sigma, const char* what) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(sigma[i]) || !(sigma[i] > 0.0)) {
      throw std::invalid_argument(std::string("fitSimilarity: ") + what +
                                  " sigmas must be finite and > 0");
    }
  }
  return sigma.cwiseInverse();
}

// Builds the problem about R0 on x.
void addResiduals(ceres::Problem& problem, double* x,
                  const std::vector<SimilarityFitPosition>& positions,
                  const std::vector<SimilarityFitAttitude>& attitudes, const Eigen::Vector3d& c,
                  const Eigen::Quaterniond& R0) {
  for (const SimilarityFitPosition& p : positions) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<PositionResidual, 3, kUnknowns>(new PositionResidual{
            p.p_source - c, p.lever_source, p.p_target, inverseOf(p.sigma_target, "position"), R0}),
        nullptr, x);
  }
  for (const SimilarityFitAttitude& a : attitudes) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<AttitudeResidual, 3, kUnknowns>(new AttitudeResidual{
            a.q_target.normalized().conjugate(), a.q_source.normalized(),
            inverseOf(a.sigma_rad, "attitude"), R0}),
        nullptr, x);
  }
}

}  // namespace

SimilarityFit fitSimilarity(const std::vector<SimilarityFitPosition>& positions,
                            const std::vector<SimilarityFitAttitude>& attitudes,
                            const Sim3& start) {
  if (positions.size() < 2) {
    throw std::invalid_argument("fitSimilarity: " + std::to_string(positions.size()) +
                                " position(s); need at least 2");
  }
  SimilarityFit fit;
  for (const SimilarityFitPosition& p : positions) fit.centroid_source += p.p_source;
  fit.centroid_source /= double(positions.size());
  const Eigen::Vector3d& c = fit.centroid_source;

  Eigen::Quaterniond R0 = start.rotation();
  double x[kUnknowns] = {std::log(start.scale()), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  Eigen::Map<Eigen::Vector3d>(x + 4) = start.apply(c);
  {
    ceres::Problem problem;
    addResiduals(problem, x, positions, attitudes, c, R0);
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;  // 7 unknowns
    options.max_num_iterations = 200;
    // Tight: an exact INS must give the exact similarity (tests check it).
    options.function_tolerance = 1e-16;
    options.gradient_tolerance = 1e-16;
    options.parameter_tolerance = 1e-14;
    options.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      throw std::invalid_argument("fitSimilarity: the solve failed: " + summary.message);
    }
  }
  // Re-centre the rotation on the solution: the covariance is then on theta
  // about the solution, a rotation of the target's axes.
  R0 = (expSO3(Eigen::Vector3d(x[1], x[2], x[3])) * R0).normalized();
  x[1] = x[2] = x[3] = 0.0;

  ceres::Problem problem;
  addResiduals(problem, x, positions, attitudes, c, R0);
  double cost = 0.0;
  ceres::CRSMatrix crs;
  problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, nullptr, &crs);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int k = crs.rows[std::size_t(row)]; k < crs.rows[std::size_t(row) + 1]; ++k) {
      J(row, crs.cols[std::size_t(k)]) = crs.values[std::size_t(k)];
    }
  }
  const Eigen::Matrix<double, 7, 7> information = J.transpose() * J;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 7, 7>> eigen(information);
  const double largest = eigen.eigenvalues().maxCoeff();
  Eigen::Matrix<double, 7, 1> inverse_eigenvalues = Eigen::Matrix<double, 7, 1>::Zero();
  for (int i = 0; i < 7; ++i) {
    // Relative to the largest: a direction 1e12 times weaker is free.
    if (eigen.eigenvalues()[i] > 1e-12 * largest) {
      inverse_eigenvalues[i] = 1.0 / eigen.eigenvalues()[i];
    } else {
      fit.rank_deficient = true;
    }
  }
  fit.covariance =
      eigen.eigenvectors() * inverse_eigenvalues.asDiagonal() * eigen.eigenvectors().transpose();

  const double s = std::exp(x[0]);
  const Eigen::Vector3d tau(x[4], x[5], x[6]);
  // p_T = s R (p_S - c) + tau  =>  translation = tau - s R c.
  fit.S_target_source = Sim3(s, R0, tau - s * (R0 * c));
  fit.sigma_log_scale = std::sqrt(fit.covariance(0, 0));
  for (int i = 0; i < 3; ++i) {
    fit.sigma_rotation_rad[i] = std::sqrt(fit.covariance(1 + i, 1 + i));
    fit.sigma_translation[i] = std::sqrt(fit.covariance(4 + i, 4 + i));
  }
  fit.cost = cost;
  fit.residuals = crs.num_rows;
  return fit;
}

}  // namespace hsmap
