#include "core/graph/noise_model.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

namespace hsmap {
namespace {

TEST(NoiseModel, SigmasWhitenPerComponent) {
  const NoiseModel noise = NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 2.0, 0.1));
  EXPECT_TRUE(noise.isDiagonal());
  const Eigen::VectorXd white = noise.whiten(Eigen::Vector3d(1.0, 1.0, 1.0));
  EXPECT_NEAR(white[0], 2.0, 1e-15);
  EXPECT_NEAR(white[1], 0.5, 1e-15);
  EXPECT_NEAR(white[2], 10.0, 1e-12);
}

TEST(NoiseModel, FullCovarianceWhitensToUnitCovariance) {
  Eigen::Matrix3d a;
  a << 2, 0.3, 0.1, 0.3, 1, -0.2, 0.1, -0.2, 0.5;
  const Eigen::Matrix3d covariance = a * a.transpose();
  const NoiseModel noise = NoiseModel::fromCovariance(covariance);
  const Eigen::MatrixXd& r = noise.sqrtInformation();
  // R Sigma R^T = I: whitened residuals have unit covariance.
  EXPECT_TRUE((r * covariance * r.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-10));
  EXPECT_TRUE(r.isUpperTriangular(1e-12));
  EXPECT_TRUE(noise.covariance().isApprox(covariance, 1e-10));
}

TEST(NoiseModel, RejectsNonPositiveSigmasAndIndefiniteCovariances) {
  try {
    NoiseModel::fromSigmas(Eigen::Vector2d(1.0, 0.0));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "NoiseModel: sigma 1 must be a finite number > 0, got 0");
  }
  EXPECT_THROW(NoiseModel::fromCovariance(-Eigen::Matrix2d::Identity()), std::invalid_argument);
  EXPECT_THROW(NoiseModel::fromSqrtInformation(Eigen::Matrix2d::Zero()), std::invalid_argument);
  EXPECT_THROW(RobustLoss::huber(0.0), std::invalid_argument);
  EXPECT_EQ(RobustLoss::cauchy(2.0).toString(), "cauchy(2)");
}

}  // namespace
}  // namespace hsmap
