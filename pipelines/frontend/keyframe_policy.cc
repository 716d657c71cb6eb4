#include "pipelines/frontend/keyframe_policy.h"

namespace hsmap {

const char* toString(KeyframeReason reason) {
  switch (reason) {
    case KeyframeReason::none: return "none";
    case KeyframeReason::parallax: return "parallax";
    case KeyframeReason::track_loss: return "track loss";
    case KeyframeReason::coverage: return "coverage";
  }
  return "?";
}

KeyframeReason decideKeyframe(const KeyframeInputs& inputs, const KeyframePolicyOptions& options) {
  if (inputs.frames_since_keyframe < options.min_interval) return KeyframeReason::none;
  if (inputs.median_parallax_deg >= options.parallax_deg) return KeyframeReason::parallax;
  if (inputs.landmarks_at_last_keyframe > 0 &&
      inputs.tracked_from_last_keyframe <
          options.min_tracked_fraction * inputs.landmarks_at_last_keyframe) {
    return KeyframeReason::track_loss;
  }
  if (inputs.coverage < options.min_coverage * inputs.coverage_at_last_keyframe) return KeyframeReason::coverage;
  return KeyframeReason::none;
}

}  // namespace hsmap
