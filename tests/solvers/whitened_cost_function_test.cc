// WhitenedCostFunction: R r and R J for diagonal and full noise models.

#include "solvers/whitened_cost_function.h"

#include <gtest/gtest.h>

#include <memory>

#include "tests/solvers/test_factors.h"

namespace hsmap {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Evaluation {
  Eigen::VectorXd residual;
  std::vector<RowMajorMatrix> jacobians;
};

Evaluation evaluate(const ceres::CostFunction& cost, const std::vector<Eigen::VectorXd>& x,
                    std::vector<bool> want = {}) {
  Evaluation out;
  out.residual.resize(cost.num_residuals());
  std::vector<const double*> parameters;
  std::vector<double*> jacobians;
  for (std::size_t k = 0; k < x.size(); ++k) {
    parameters.push_back(x[k].data());
    out.jacobians.emplace_back(RowMajorMatrix::Constant(cost.num_residuals(), x[k].size(), 42.0));
    const bool wanted = want.empty() || want[k];
    jacobians.push_back(wanted ? out.jacobians.back().data() : nullptr);
  }
  EXPECT_TRUE(cost.Evaluate(parameters.data(), out.residual.data(), jacobians.data()));
  return out;
}

class WhitenedCostFunctionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    A_ = {Eigen::MatrixXd::Random(3, 2), Eigen::MatrixXd::Random(3, 4)};
    b_ = Eigen::VectorXd::Random(3);
    x_ = {Eigen::VectorXd::Random(2), Eigen::VectorXd::Random(4)};
  }
  std::unique_ptr<ceres::CostFunction> raw() const {
    return std::make_unique<test::LinearCostFunction>(A_, b_);
  }
  std::vector<Eigen::MatrixXd> A_;
  Eigen::VectorXd b_;
  std::vector<Eigen::VectorXd> x_;
};

TEST_F(WhitenedCostFunctionTest, DiagonalNoiseScalesResidualsAndJacobianRows) {
  const NoiseModel noise = NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 2.0, 0.1));
  const WhitenedCostFunction whitened(raw(), noise);
  EXPECT_EQ(whitened.num_residuals(), 3);
  EXPECT_EQ(whitened.parameter_block_sizes(), (std::vector<int32_t>{2, 4}));
  const Evaluation e = evaluate(whitened, x_);
  const Eigen::VectorXd r = A_[0] * x_[0] + A_[1] * x_[1] - b_;
  const Eigen::Vector3d scale(2.0, 0.5, 10.0);
  EXPECT_LT((e.residual - scale.asDiagonal() * r).norm(), 1e-14);
  EXPECT_LT((e.jacobians[0] - scale.asDiagonal() * A_[0]).norm(), 1e-14);
  EXPECT_LT((e.jacobians[1] - scale.asDiagonal() * A_[1]).norm(), 1e-14);
}

TEST_F(WhitenedCostFunctionTest, FullNoiseMultipliesBySqrtInformation) {
  Eigen::Matrix3d L = Eigen::Matrix3d::Random();
  const Eigen::Matrix3d covariance = L * L.transpose() + 0.5 * Eigen::Matrix3d::Identity();
  const NoiseModel noise = NoiseModel::fromCovariance(covariance);
  ASSERT_FALSE(noise.isDiagonal());
  const Eigen::MatrixXd R = noise.sqrtInformation();
  const WhitenedCostFunction whitened(raw(), noise);
  const Evaluation e = evaluate(whitened, x_);
  const Eigen::VectorXd r = A_[0] * x_[0] + A_[1] * x_[1] - b_;
  EXPECT_LT((e.residual - R * r).norm(), 1e-12);
  EXPECT_LT((e.jacobians[0] - R * A_[0]).norm(), 1e-12);
  EXPECT_LT((e.jacobians[1] - R * A_[1]).norm(), 1e-12);
  // The whitened cost is the Mahalanobis distance.
  EXPECT_NEAR(e.residual.squaredNorm(), r.dot(covariance.inverse() * r), 1e-10);
}

TEST_F(WhitenedCostFunctionTest, LeavesJacobiansCeresDidNotAskForAlone) {
  const WhitenedCostFunction whitened(raw(), NoiseModel::fromCovariance(2.0 * Eigen::Matrix3d::Identity() +
                                                                       Eigen::Matrix3d::Constant(0.5)));
  const Evaluation e = evaluate(whitened, x_, {false, true});
  EXPECT_TRUE((e.jacobians[0].array() == 42.0).all());
  EXPECT_FALSE((e.jacobians[1].array() == 42.0).all());
  // Residuals only (no Jacobian array at all).
  std::vector<const double*> parameters{x_[0].data(), x_[1].data()};
  Eigen::Vector3d residual;
  EXPECT_TRUE(whitened.Evaluate(parameters.data(), residual.data(), nullptr));
  EXPECT_LT((residual - e.residual).norm(), 1e-14);
}

TEST_F(WhitenedCostFunctionTest, RejectsANoiseModelOfTheWrongDimension) {
  try {
    WhitenedCostFunction whitened(raw(), NoiseModel::isotropic(2, 1.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "WhitenedCostFunction: the cost function returns 3 residuals but the noise model "
                 "has dimension 2");
  }
}

}  // namespace
}  // namespace hsmap
