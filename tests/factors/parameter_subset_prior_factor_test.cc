#include "factors/parameter_subset_prior_factor.h"

#include <gtest/gtest.h>

#include <ceres/cost_function.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

TEST(ParameterSubsetPriorFactor, ResidualIsTheFreeComponentsOffTheirPrior) {
  const ParameterSubsetPriorFactor factor("Prior", K(0), {1.0, 2.0, 3.0}, {0.5, 0.0, 2.0});
  EXPECT_EQ(factor.freeParameters(), (std::vector<int>{0, 2}));
  const auto cost = factor.createCostFunction();
  const double k[3] = {1.5, 7.0, 1.0};
  const double* parameters[1] = {k};
  double residuals[2];
  ASSERT_TRUE(cost->Evaluate(parameters, residuals, nullptr));
  EXPECT_DOUBLE_EQ(residuals[0], 0.5);   // the held component (7 against 2) has no residual
  EXPECT_DOUBLE_EQ(residuals[1], -2.0);
  EXPECT_EQ(ParameterSubsetPriorFactor::heldComponents({0.5, 0.0, 2.0}), (std::vector<int>{1}));
}

TEST(ParameterSubsetPriorFactor, NamesItselfInEveryError) {
  auto message = [](auto make) {
    try {
      make();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([] { ParameterSubsetPriorFactor("Prior", K(0), {1.0, 2.0}, {1.0}); }),
            "Prior: 2 prior values but 1 sigmas");
  EXPECT_EQ(message([] { ParameterSubsetPriorFactor("Prior", K(0), {1.0}, {0.0}); }),
            "Prior: every sigma is 0, nothing to estimate (hold the block constant instead)");
  EXPECT_EQ(message([] { ParameterSubsetPriorFactor("Prior", K(0), {1.0}, {-1.0}); }),
            "Prior: sigma of parameter 0 must be finite and >= 0, got -1.000000");
}

}  // namespace
}  // namespace hsmap
