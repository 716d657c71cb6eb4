#pragma once
// NoiseModel: the Gaussian noise of a factor's residual, held as the upper
// triangular square-root information matrix R (R^T R = Sigma^-1), so that the
// whitened residual R * r has unit covariance and the cost is 0.5 |R r|^2.
//
// RobustLoss: an optional M-estimator applied to the whitened squared norm
// (Huber or Cauchy with a scale in whitened units, i.e. "sigmas"), used on
// visual factors so that outlier matches cannot dominate the solution.

#include <Eigen/Core>
#include <string>

namespace hsmap {

class NoiseModel {
 public:
  // Independent residual components with standard deviations `sigmas` (> 0).
  static NoiseModel fromSigmas(const Eigen::VectorXd& sigmas);
  // `dimension` components, each with standard deviation `sigma` (> 0).
  static NoiseModel isotropic(int dimension, double sigma);
  // A full covariance (symmetric positive definite).
  static NoiseModel fromCovariance(const Eigen::MatrixXd& covariance);
  // A square-root information matrix given directly (square, invertible).
  static NoiseModel fromSqrtInformation(const Eigen::MatrixXd& sqrt_information);

  int dimension() const { return static_cast<int>(sqrt_information_.rows()); }
  const Eigen::MatrixXd& sqrtInformation() const { return sqrt_information_; }
  // True when R is diagonal, so whitening is a per-component scale.
  bool isDiagonal() const { return diagonal_; }
  Eigen::MatrixXd covariance() const;

  Eigen::VectorXd whiten(const Eigen::VectorXd& residual) const;

 private:
  explicit NoiseModel(Eigen::MatrixXd sqrt_information, bool diagonal);
  Eigen::MatrixXd sqrt_information_;
  bool diagonal_;
};

struct RobustLoss {
  enum class Kind { none, huber, cauchy };
  Kind kind = Kind::none;
  double scale = 1.0;  // in whitened units: residuals beyond `scale` sigmas are down-weighted

  static RobustLoss none() { return {}; }
  static RobustLoss huber(double scale);
  static RobustLoss cauchy(double scale);
  std::string toString() const;  // "none", "huber(1.5)", "cauchy(2)"
};

}  // namespace hsmap
