// Which stages the variants of a compare share (pipelines/compare/compare_plan.h).

#include "pipelines/compare/compare_plan.h"

#include <gtest/gtest.h>

#include "pipelines/compare/variant_list.h"

namespace hsmap {
namespace {

const std::string kStamp = "rgb/frames.csv 100 1\nnav/ins.csv 200 2\n";

TEST(ComparePlan, JointTakesFrontendGeorefAndSurfaceFromSequential) {
  RunOptions base;
  base.survey = "/data/dive7";
  const auto plans = planCompare(allCompareVariants(), base, kStamp);
  ASSERT_EQ(plans.size(), 4u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_FALSE(plans[i].donor) << toString(plans[i].variant);
    EXPECT_TRUE(plans[i].shared.empty()) << toString(plans[i].variant);
  }
  EXPECT_EQ(plans[3].variant, Variant::joint);
  ASSERT_TRUE(plans[3].donor);
  EXPECT_EQ(*plans[3].donor, Variant::sequential);
  EXPECT_EQ(plans[3].shared, (std::vector<StageId>{StageId::frontend, StageId::georef, StageId::surface}));
}

TEST(ComparePlan, TheVariantListedFirstRunsTheSharedStages) {
  RunOptions base;
  const auto plans = planCompare({Variant::joint, Variant::sequential}, base, kStamp);
  EXPECT_FALSE(plans[0].donor);
  ASSERT_TRUE(plans[1].donor);
  EXPECT_EQ(*plans[1].donor, Variant::joint);
  EXPECT_EQ(plans[1].shared.size(), 3u);
}

TEST(ComparePlan, AStageOptionThatDiffersEndsTheSharing) {
  // The surface mode is the surface stage's option: with it the two would
  // still share frontend and georef; planned on one base they share all three.
  RunOptions sparse;
  sparse.surface.mode = SurfaceMode::sparse;
  const auto plans = planCompare({Variant::sequential, Variant::joint}, sparse, kStamp);
  EXPECT_EQ(plans[1].shared.size(), 3u);
  const auto alone = planCompare({Variant::planar, Variant::stacked}, sparse, kStamp);
  EXPECT_FALSE(alone[1].donor);
}

}  // namespace
}  // namespace hsmap
