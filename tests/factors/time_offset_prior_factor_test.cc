#include "factors/time_offset_prior_factor.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using test::evaluate;
using test::scalarBlock;
using test::tangentJacobiansMatchNumeric;

TEST(TimeOffsetPriorFactor, NamesItsMeasurementAndKey) {
  const TimeOffsetPriorFactor factor(D(0), 0.015, NoiseModel::isotropic(1, 0.05));
  EXPECT_EQ(factor.name(), "TimeOffsetPriorFactor");
  EXPECT_EQ(factor.keys(), (std::vector<Key>{D(0)}));
  EXPECT_EQ(factor.createCostFunction()->parameter_block_sizes(), (std::vector<int32_t>{1}));
}

TEST(TimeOffsetPriorFactor, ResidualIsTheOffsetMinusThePrior) {
  const TimeOffsetPriorFactor factor(D(0), 0.015, NoiseModel::isotropic(1, 0.05));
  const auto evaluation = evaluate(*factor.createCostFunction(), {scalarBlock(0.02)});
  ASSERT_TRUE(evaluation.ok);
  EXPECT_NEAR(evaluation.residual[0], 0.005, 1e-15);
  EXPECT_DOUBLE_EQ(evaluation.jacobians[0](0, 0), 1.0);
  EXPECT_EQ(evaluate(*factor.createCostFunction(), {scalarBlock(0.015)}).residual[0], 0.0);
  EXPECT_TRUE(tangentJacobiansMatchNumeric(*factor.createCostFunction(), {scalarBlock(-0.3)}));
}

TEST(TimeOffsetPriorFactor, RejectsBadArguments) {
  try {
    TimeOffsetPriorFactor(D(0), 0.0, NoiseModel::isotropic(2, 0.05));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "TimeOffsetPriorFactor: the noise model has dimension 2, expected 1 (one per "
                 "residual component)");
  }
  try {
    TimeOffsetPriorFactor(D(0), std::numeric_limits<double>::infinity(),
                          NoiseModel::isotropic(1, 0.05));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "TimeOffsetPriorFactor: prior must be finite, got inf");
  }
}

}  // namespace
}  // namespace hsmap
