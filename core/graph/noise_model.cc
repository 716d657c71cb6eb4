#include "core/graph/noise_model.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

NoiseModel::NoiseModel(Eigen::MatrixXd sqrt_information, bool diagonal)
    : sqrt_information_(std::move(sqrt_information)), diagonal_(diagonal) {}

NoiseModel NoiseModel::fromSigmas(const Eigen::VectorXd& sigmas) {
  if (sigmas.size() == 0) throw std::invalid_argument("NoiseModel: sigmas must not be empty");
  for (Eigen::Index i = 0; i < sigmas.size(); ++i) {
    if (!std::isfinite(sigmas[i]) || sigmas[i] <= 0.0) {
      std::ostringstream message;
      message << "NoiseModel: sigma " << i << " must be a finite number > 0, got " << sigmas[i];
      throw std::invalid_argument(message.str());
    }
  }
  return NoiseModel(sigmas.cwiseInverse().asDiagonal(), true);
}

NoiseModel NoiseModel::isotropic(int dimension, double sigma) {
  if (dimension <= 0) throw std::invalid_argument("NoiseModel: dimension must be > 0");
  return fromSigmas(Eigen::VectorXd::Constant(dimension, sigma));
}

NoiseModel NoiseModel::fromCovariance(const Eigen::MatrixXd& covariance) {
  if (covariance.rows() == 0 || covariance.rows() != covariance.cols()) {
    throw std::invalid_argument("NoiseModel: covariance must be a non-empty square matrix");
  }
  if (!covariance.isApprox(covariance.transpose(), 1e-9)) {
    throw std::invalid_argument("NoiseModel: covariance must be symmetric");
  }
  const Eigen::LLT<Eigen::MatrixXd> covariance_llt(covariance);
  if (covariance_llt.info() != Eigen::Success) {
    throw std::invalid_argument("NoiseModel: covariance must be positive definite");
  }
  // Sigma^-1 = R^T R with R upper triangular: R = L^T where L L^T = Sigma^-1.
  const Eigen::MatrixXd information =
      covariance_llt.solve(Eigen::MatrixXd::Identity(covariance.rows(), covariance.cols()));
  const Eigen::LLT<Eigen::MatrixXd> llt(information);
  if (llt.info() != Eigen::Success) {
    throw std::invalid_argument("NoiseModel: covariance must be positive definite");
  }
  const Eigen::MatrixXd upper = llt.matrixU();
  return NoiseModel(upper, upper.isDiagonal());
}

NoiseModel NoiseModel::fromSqrtInformation(const Eigen::MatrixXd& sqrt_information) {
  if (sqrt_information.rows() == 0 || sqrt_information.rows() != sqrt_information.cols()) {
    throw std::invalid_argument("NoiseModel: square-root information must be a non-empty square matrix");
  }
  if (!sqrt_information.allFinite() ||
      std::abs(sqrt_information.determinant()) < 1e-300) {
    throw std::invalid_argument("NoiseModel: square-root information must be finite and invertible");
  }
  return NoiseModel(sqrt_information, sqrt_information.isDiagonal());
}

Eigen::MatrixXd NoiseModel::covariance() const {
  const Eigen::MatrixXd information = sqrt_information_.transpose() * sqrt_information_;
  return information.inverse();
}

Eigen::VectorXd NoiseModel::whiten(const Eigen::VectorXd& residual) const {
  if (residual.size() != dimension()) {
    throw std::invalid_argument("NoiseModel: residual of size " + std::to_string(residual.size()) +
                                " does not match dimension " + std::to_string(dimension()));
  }
  return sqrt_information_ * residual;
}

RobustLoss RobustLoss::huber(double scale) {
  if (!(scale > 0.0)) throw std::invalid_argument("RobustLoss: Huber scale must be > 0");
  return {Kind::huber, scale};
}

RobustLoss RobustLoss::cauchy(double scale) {
  if (!(scale > 0.0)) throw std::invalid_argument("RobustLoss: Cauchy scale must be > 0");
  return {Kind::cauchy, scale};
}

std::string RobustLoss::toString() const {
  std::ostringstream text;
  switch (kind) {
    case Kind::none: return "none";
    case Kind::huber: text << "huber(" << scale << ")"; break;
    case Kind::cauchy: text << "cauchy(" << scale << ")"; break;
  }
  return text.str();
}

}  // namespace hsmap
