#include "pipelines/frontend/keyframe_policy.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

KeyframeInputs steady() {
  KeyframeInputs in;
  in.median_parallax_deg = 0.5;
  in.tracked_landmarks = 200;
  in.landmarks_at_last_keyframe = 220;
  in.tracked_from_last_keyframe = 200;
  in.coverage = 0.8;
  in.coverage_at_last_keyframe = 0.85;
  in.frames_since_keyframe = 5;
  return in;
}

TEST(KeyframePolicy, NoKeyframeWhileTheViewBarelyChanges) {
  EXPECT_EQ(decideKeyframe(steady(), KeyframePolicyOptions{}), KeyframeReason::none);
}

TEST(KeyframePolicy, ParallaxMakesAKeyframe) {
  KeyframeInputs in = steady();
  in.median_parallax_deg = 2.6;
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::parallax);
  in.median_parallax_deg = 2.4;
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::none);
}

TEST(KeyframePolicy, LosingTheLastKeyframesLandmarksMakesAKeyframe) {
  KeyframeInputs in = steady();
  in.tracked_from_last_keyframe = 120;  // 55 % of 220
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::track_loss);
}

TEST(KeyframePolicy, ShrinkingCoverageMakesAKeyframeButABarePatchDoesNot) {
  KeyframeInputs in = steady();
  in.coverage = 0.4;  // below half of 0.85
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::coverage);
  // A scene that never covered much of the grid is not a reason in itself.
  in.coverage_at_last_keyframe = 0.45;
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::none);
}

TEST(KeyframePolicy, NoKeyframeSoonerThanTheMinimumInterval) {
  KeyframeInputs in = steady();
  in.median_parallax_deg = 10.0;
  in.frames_since_keyframe = 1;
  EXPECT_EQ(decideKeyframe(in, KeyframePolicyOptions{}), KeyframeReason::none);
}

}  // namespace
}  // namespace hsmap
