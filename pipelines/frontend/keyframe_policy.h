#pragma once
// When a tracked frame becomes a keyframe. Three reasons, checked in order:
//   - parallax: the median angle, at its landmarks, between the rays from
//     the last keyframe and from this frame exceeds `parallax_deg`. New
//     landmarks are triangulated between keyframes, so this sets their depth
//     precision; an angle (not pixels) holds for any altitude and focal length;
//   - track loss: fewer than `min_tracked_fraction` of the landmarks the last
//     keyframe saw are still tracked (the view is leaving the mapped ground);
//   - coverage: the share of grid cells holding a tracked landmark fell
//     below `min_coverage` times its value at the last keyframe (parts of the
//     image lost their landmarks; relative, so a scene with bare patches does
//     not make every frame a keyframe).
// A keyframe needs at least `min_interval` frames since the last one, so a
// burst of bad frames cannot fill the map with near-duplicates.

#include <string>

namespace hsmap {

struct KeyframePolicyOptions {
  double parallax_deg = 2.5;
  double min_tracked_fraction = 0.6;
  double min_coverage = 0.5;
  int min_interval = 2;
};

struct KeyframeInputs {
  double median_parallax_deg = 0.0;
  int tracked_landmarks = 0;              // in this frame (pose inliers)
  int landmarks_at_last_keyframe = 0;     // observed by the last keyframe
  int tracked_from_last_keyframe = 0;     // of those, still tracked here
  double coverage = 1.0;                  // fraction of grid cells with a tracked landmark
  double coverage_at_last_keyframe = 1.0; // the same for the last keyframe's landmarks
  int frames_since_keyframe = 0;
};

enum class KeyframeReason { none, parallax, track_loss, coverage };
const char* toString(KeyframeReason reason);

KeyframeReason decideKeyframe(const KeyframeInputs& inputs, const KeyframePolicyOptions& options);

}  // namespace hsmap
