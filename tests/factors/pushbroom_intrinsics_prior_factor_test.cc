#include "factors/pushbroom_intrinsics_prior_factor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "tests/factors/factor_test_support.h"

namespace hsmap {
namespace {

using Intrinsics = PushbroomIntrinsicsPriorFactor::Intrinsics;

const Intrinsics kPrior{1500.0, 960.0, 0.02, -0.005};

TEST(PushbroomIntrinsicsPriorFactor, ResidualHasOneRowPerParameterWithASigma) {
  const PushbroomIntrinsicsPriorFactor factor(K(0), kPrior, {15.0, 3.0, 0.02, 0.0});
  EXPECT_EQ(factor.freeParameters(), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(factor.noise().dimension(), 3);
  const Eigen::VectorXd r = test::residualAt(
      *factor.createCostFunction(), {test::vectorBlock(Eigen::Vector4d(1510.0, 957.0, 0.03, 0.5))});
  ASSERT_EQ(r.size(), 3);
  EXPECT_NEAR(r[0], 10.0, 1e-12);
  EXPECT_NEAR(r[1], -3.0, 1e-12);
  EXPECT_NEAR(r[2], 0.01, 1e-12);
  // Whitened by the sigmas: 10 px at 15 px is 2/3 of a sigma.
  EXPECT_NEAR(factor.noise().whiten(r)[0], 10.0 / 15.0, 1e-12);
  EXPECT_EQ(PushbroomIntrinsicsPriorFactor::heldParameters({15.0, 3.0, 0.02, 0.0}), (std::vector<int>{3}));
}

TEST(PushbroomIntrinsicsPriorFactor, JacobianMatchesNumericDifferences) {
  const PushbroomIntrinsicsPriorFactor factor(K(0), kPrior, {15.0, 0.0, 0.02, 0.01});
  EXPECT_TRUE(test::tangentJacobiansMatchNumeric(
      *factor.createCostFunction(), {test::vectorBlock(Eigen::Vector4d(1490.0, 961.0, 0.01, 0.002))}));
}

TEST(PushbroomIntrinsicsPriorFactor, RejectsNoSigmaANegativeSigmaAndANonFinitePrior) {
  EXPECT_THROW(PushbroomIntrinsicsPriorFactor(K(0), kPrior, {0.0, 0.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(PushbroomIntrinsicsPriorFactor(K(0), kPrior, {-1.0, 1.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(PushbroomIntrinsicsPriorFactor(K(0), {NAN, 960.0, 0.0, 0.0}, {1.0, 1.0, 0.0, 0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
