#pragma once
// Every frame posed against the geo-referenced landmarks: the front-end
// recorded, for each frame it posed, the landmarks it tracked and where
// (FrontendResult::frame_observations). After the bundle adjustment has
// moved those landmarks into W, each frame is posed again by PnP RANSAC and
// the motion-only refinement (pipelines/frontend/frame_pose_estimator.h),
// started from its prediction: its front-end pose relative to the nearest
// keyframe, carried along by that keyframe's adjusted pose. Frames are
// independent, so they are posed in parallel (oneTBB), each solve on one
// thread.

#include <functional>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "pipelines/frontend/frame_pose_estimator.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/frontend/visual_map.h"

namespace hsmap {

struct FrameToRepose {
  int frame = -1;      // survey frame index
  SE3d prediction;     // T_W_C to start from (and to keep if PnP fails)
};

struct Repose {
  bool ok = false;
  SE3d T_W_C;
  int inliers = 0;
  double rms_px = 0.0;
};

// One result per entry of `frames`, from the front-end's observations of
// each frame (FrontendResult::observationsOfFrame); landmarks no longer
// valid in `map` are skipped.
// `progress(done)` is called (serialised, from any worker) as frames finish.
std::vector<Repose> reposeFrames(const std::vector<FrameToRepose>& frames,
                                 const FrontendResult& frontend,
                                 const VisualMap& map, const PinholeRadtanCamera& camera,
                                 const PoseEstimatorOptions& options,
                                 const std::function<void(int)>& progress = {});

}  // namespace hsmap
