#include "factors/positive_depth.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

namespace hsmap {
namespace {

using Jet1 = ceres::Jet<double, 1>;

TEST(SoftPositiveDepth, LeavesDepthsAtOrBeyondTheFloorUnchanged) {
  EXPECT_EQ(softPositiveDepth(kMinimumDepthM), kMinimumDepthM);
  EXPECT_EQ(softPositiveDepth(0.5), 0.5);
  EXPECT_EQ(softPositiveDepth(30.0), 30.0);
}

TEST(SoftPositiveDepth, IsContinuousWithUnitSlopeAtTheFloor) {
  const Jet1 below = softPositiveDepth(Jet1(kMinimumDepthM - 1e-12, 0));
  const Jet1 above = softPositiveDepth(Jet1(kMinimumDepthM, 0));
  EXPECT_NEAR(below.a, kMinimumDepthM, 1e-11);
  EXPECT_NEAR(below.v[0], 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(above.v[0], 1.0);
}

TEST(SoftPositiveDepth, IsPositiveAndIncreasingBehindTheCamera) {
  double previous = 0.0;
  for (double z : {-1e6, -100.0, -1.0, -1e-3, 0.0, 1e-3, 0.009}) {
    const double floored = softPositiveDepth(z);
    EXPECT_GT(floored, previous) << "z = " << z;
    EXPECT_LT(floored, kMinimumDepthM) << "z = " << z;
    previous = floored;
  }
  // z_min^2 / (2 z_min - z) at z = 0 is z_min / 2.
  EXPECT_DOUBLE_EQ(softPositiveDepth(0.0), kMinimumDepthM / 2.0);
}

}  // namespace
}  // namespace hsmap
