#include "factors/second_difference_prior_factor.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;

TEST(SecondDifferencePriorFactor, ResidualIsTheSecondDifference) {
  const SecondDifferencePriorFactor factor(C(0), C(1), C(2), NoiseModel::isotropic(1, 0.1));
  EXPECT_EQ(factor.name(), "SecondDifferencePriorFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{C(0), C(1), C(2)}));
  // A straight line has none; a bend has it.
  EXPECT_NEAR(evaluate(*factor.createCostFunction(), {scalarBlock(0.1), scalarBlock(0.2), scalarBlock(0.3)}).residual[0],
              0.0, 1e-15);
  EXPECT_NEAR(evaluate(*factor.createCostFunction(), {scalarBlock(0.1), scalarBlock(0.2), scalarBlock(0.5)}).residual[0],
              0.2, 1e-15);
  EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(),
                                           {scalarBlock(0.4), scalarBlock(-0.2), scalarBlock(1.5)}));
  EXPECT_THROW(SecondDifferencePriorFactor(C(0), C(1), C(2), NoiseModel::isotropic(2, 0.1)), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
