#include "factors/pinhole_intrinsics_prior_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using Intrinsics = PinholeIntrinsicsPriorFactor::Intrinsics;

const Intrinsics kPrior{800.0, 801.0, 480.0, 270.0, -0.08, 0.02, 4e-4, -3e-4, 0.0};

Eigen::VectorXd block(const Intrinsics& k) { return Eigen::Map<const Eigen::VectorXd>(k.data(), 9); }

TEST(PinholeIntrinsicsPriorFactor, ResidualHasOneRowPerParameterWithASigma) {
  const Intrinsics sigmas{8.0, 8.0, 4.0, 4.0, 0.02, 0.0, 0.0, 0.0, 0.0};
  const PinholeIntrinsicsPriorFactor factor(K(1), kPrior, sigmas);
  EXPECT_EQ(factor.freeParameters(), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(factor.noise().dimension(), 5);
  const Eigen::VectorXd r = test::residualAt(
      *factor.createCostFunction(),
      {test::vectorBlock(block({808.0, 800.0, 483.0, 268.0, -0.07, 0.5, 0.1, 0.1, 0.1}))});
  ASSERT_EQ(r.size(), 5);
  EXPECT_NEAR(r[0], 8.0, 1e-12);
  EXPECT_NEAR(r[1], -1.0, 1e-12);
  EXPECT_NEAR(r[2], 3.0, 1e-12);
  EXPECT_NEAR(r[3], -2.0, 1e-12);
  EXPECT_NEAR(r[4], 0.01, 1e-12);
  // Whitened by the sigmas: 8 px at 8 px is one sigma.
  EXPECT_NEAR(factor.noise().whiten(r)[0], 1.0, 1e-12);
  EXPECT_EQ(PinholeIntrinsicsPriorFactor::heldParameters(sigmas), (std::vector<int>{5, 6, 7, 8}));
}

TEST(PinholeIntrinsicsPriorFactor, JacobianMatchesNumericDifferences) {
  const PinholeIntrinsicsPriorFactor factor(K(1), kPrior, {8.0, 0.0, 4.0, 4.0, 0.02, 0.02, 0.001, 0.0, 0.02});
  EXPECT_TRUE(test::tangentJacobiansMatchNumeric(
      *factor.createCostFunction(),
      {test::vectorBlock(block({795.0, 801.0, 478.0, 271.0, -0.07, 0.01, 0.0, 0.0, 0.01}))}));
}

TEST(PinholeIntrinsicsPriorFactor, RejectsNoSigmaANegativeSigmaAndANonFinitePrior) {
  EXPECT_THROW(PinholeIntrinsicsPriorFactor(K(1), kPrior, Intrinsics{}), std::invalid_argument);
  EXPECT_THROW(PinholeIntrinsicsPriorFactor(K(1), kPrior, {-1.0, 1.0, 0, 0, 0, 0, 0, 0, 0}),
               std::invalid_argument);
  Intrinsics bad = kPrior;
  bad[2] = NAN;
  EXPECT_THROW(PinholeIntrinsicsPriorFactor(K(1), bad, {1.0, 1.0, 0, 0, 0, 0, 0, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
