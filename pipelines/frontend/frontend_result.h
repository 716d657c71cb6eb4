#pragma once
// FrontendResult: everything the front-end produces for one survey — the
// sparse map, a record per frame (pose, statistics, time per step), the
// tracking losses, the map segments and how they were linked — as written
// to RUN/frontend/ (frontend_outputs.h, docs/SURVEY_FORMAT.md).
//
// Frames: F is the front-end's frame (that of the reference segment, up to
// scale). A frame is "posed" when its T_F_C comes from vision in a segment
// that is linked into F.

#include <array>
#include <string>
#include <vector>

#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "pipelines/frontend/visual_map.h"

namespace hsmap {

// What happened to a frame (frame_stats.csv `status`).
enum class FrameStatus {
  tracking,       // posed by PnP on tracked landmarks
  initialising,   // posed once its segment initialised (buffered frames), or waiting to
  lost,           // not posed: too few tracks / inliers, or its segment could not be linked
  no_texture,     // not posed: black, over-exposed, flat or blurred (see the loss reason)
  undecodable,    // not posed: the image could not be decoded
};
const char* toString(FrameStatus status);
// Inverse of toString; throws std::invalid_argument for an unknown name.
FrameStatus parseFrameStatus(const std::string& name);

// The steps whose time is measured per frame (milliseconds).
enum class FrontendStep { decode, preprocess, track, detect, pnp, triangulate, ba, count };
inline constexpr int kFrontendStepCount = static_cast<int>(FrontendStep::count);
const char* toString(FrontendStep step);

using StepTimesMs = std::array<double, kFrontendStepCount>;

struct FrameRecord {
  int index = 0;  // survey frame index
  double t = 0.0;
  bool posed = false;
  SE3d T_F_C;
  int segment = -1;         // map segment it was tracked in (-1: none)
  FrameStatus status = FrameStatus::lost;
  bool keyframe = false;
  int keyframe_id = -1;
  int tracked = 0;          // KLT tracks alive in this frame
  int inliers = 0;          // landmarks the pose was computed from (after refinement)
  int new_corners = 0;      // corners detected in this frame
  StepTimesMs ms{};         // time per step
};

struct TrackingLoss {
  int first_frame = 0;  // first frame not posed
  int last_frame = 0;   // last frame not posed
  std::string reason;   // why the first frame was lost (e.g. "no texture: dark (mean 0.0 DN)")
};

struct SegmentRecord {
  int id = 0;
  int first_frame = 0;
  int last_frame = 0;
  int keyframes = 0;
  bool reference = false;  // its frame is F
  bool linked = false;     // expressed in F (the reference is linked by definition)
  Sim3 S_F_S;              // segment frame -> F
  double ins_rms_m = 0.0;  // residual of its INS fit (0 when not fitted)
  std::string note;        // e.g. "linked through the INS (rms 0.05 m)" or why not
};

struct FrontendResult {
  VisualMap map;
  std::vector<FrameRecord> frames;
  std::vector<TrackingLoss> losses;
  std::vector<SegmentRecord> segments;
  StepTimesMs total_ms{};   // per step, over all frames
  double wall_time_s = 0.0;
  double frames_per_second = 0.0;           // frames / wall time, decoding included
  // Frames per second of the tracking thread alone (track, detect, pnp,
  // triangulate, ba: the images already decoded and pre-processed).
  double trackingFramesPerSecond() const;
  double peak_memory_mb = 0.0;
  std::vector<std::string> warnings;  // undecodable frames, unlinked segments, ...

  int posedFrameCount() const;
  // One paragraph: frames posed, keyframes, landmarks, losses, speed.
  std::string summary() const;
};

}  // namespace hsmap
