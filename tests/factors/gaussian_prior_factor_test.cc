#include "factors/gaussian_prior_factor.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;
using test::vectorBlock;

TEST(GaussianPriorFactor, ResidualIsTheValueMinusThePrior) {
  const GaussianPriorFactor factor(M(0), Eigen::Vector2d(-1.0, 0.5), NoiseModel::isotropic(2, 2.0));
  EXPECT_EQ(factor.name(), "GaussianPriorFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{M(0)}));
  const auto evaluation = evaluate(*factor.createCostFunction(), {vectorBlock(Eigen::Vector2d(0.5, 0.25))});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_DOUBLE_EQ(evaluation.residual[0], 1.5);
  EXPECT_DOUBLE_EQ(evaluation.residual[1], -0.25);
  EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {vectorBlock(Eigen::Vector2d(3.0, -2.0))}));
  const GaussianPriorFactor scalar(C(4), Eigen::VectorXd::Constant(1, 0.2), NoiseModel::isotropic(1, 0.3));
  EXPECT_TRUE(tangentJacobiansMatchNumeric(*scalar.createCostFunction(), {scalarBlock(0.7)}));
}

TEST(GaussianPriorFactor, RejectsBadArguments) {
  EXPECT_THROW(GaussianPriorFactor(C(0), Eigen::VectorXd(), NoiseModel::isotropic(1, 1.0)), std::invalid_argument);
  EXPECT_THROW(GaussianPriorFactor(C(0), Eigen::VectorXd::Constant(1, 0.1), NoiseModel::isotropic(2, 1.0)),
               std::invalid_argument);
  EXPECT_THROW(GaussianPriorFactor(C(0), Eigen::VectorXd::Constant(1, std::numeric_limits<double>::quiet_NaN()),
                                   NoiseModel::isotropic(1, 1.0)),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
