#pragma once
// FrontendResult: everything the front-end produces for one survey — the
// sparse map, a record per frame (pose, statistics, time per step), the
// tracking losses, the map segments and how they were linked, and the 2D-3D
// observations every posed frame's pose rests on — as written to
// RUN/frontend/ (frontend_outputs.h, docs/SURVEY_FORMAT.md).
//
// Frames: F is the front-end's frame (that of the reference segment, up to
// scale). A frame is "posed" when its T_F_C comes from vision in a segment
// that is linked into F.

#include <array>
#include <span>
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

// One 2D-3D correspondence a posed frame's pose was computed from: landmark
// `landmark` (an id of FrontendResult::map) measured at pixel (u, v) in
// survey frame `frame` — distorted, as measured, like the keyframe
// observations. For a frame posed by PnP these are the final inliers after
// the motion-only refinement (PoseEstimate::inliers); for the two keyframes
// that start a segment, the landmarks of the two-view start. They let a
// later stage re-pose every frame against the refined landmarks (PnP +
// motion-only refinement), not only the keyframes.
//
// float pixels: KLT measures in float, so nothing is lost, and each of the
// ~3 million observations of a 100 m transect (6,200 frames, ~500 each)
// takes 16 bytes.
struct FrameObservation {
  int frame = 0;      // survey frame index (FrameRecord::index)
  int landmark = -1;  // landmark id in the map
  float u = 0.0f;
  float v = 0.0f;
};

struct TrackingLoss {
  int first_frame = 0;  // first frame not posed
  int last_frame = 0;   // last frame not posed
  std::string reason;   // why the first frame was lost (e.g. "no texture: dark (mean 0.0 DN)")
};

// How a segment came into F (segments.csv `link`; docs/FRONTEND.md,
// "Linking segments").
enum class SegmentLink {
  reference,  // its frame is F
  vision,     // joined to an earlier segment by matching their landmarks (segment_joiner.h)
  ins,        // fitted to the INS (segment_linker.h), no view overlapping an earlier segment's
  none,       // not linked: its frames are reported lost
};
const char* toString(SegmentLink link);
// Inverse of toString; throws std::invalid_argument for an unknown name.
SegmentLink parseSegmentLink(const std::string& name);

struct SegmentRecord {
  int id = 0;
  int first_frame = 0;
  int last_frame = 0;
  int keyframes = 0;
  bool reference = false;  // its frame is F
  bool linked = false;     // expressed in F (the reference is linked by definition)
  Sim3 S_F_S;              // segment frame -> F
  double ins_rms_m = 0.0;  // residual of its INS fit (0 when not fitted)
  SegmentLink link = SegmentLink::none;
  // 1-sigma of S_F_S.scale() (0 for the reference; see docs/FRONTEND.md).
  double scale_sigma = 0.0;
  int joined_to = -1;      // the segment it was joined to by vision (-1: none)
  std::string note;        // e.g. "joined to segment 0 by vision: ..." or why not linked
};

struct FrontendResult {
  VisualMap map;
  std::vector<FrameRecord> frames;
  std::vector<TrackingLoss> losses;
  std::vector<SegmentRecord> segments;
  // Of every posed frame, keyframes included; sorted by frame, then landmark,
  // each pair once. Every landmark is a valid one of `map` (observations of
  // landmarks the map later removed are dropped), so a frame may keep fewer
  // than its FrameRecord::inliers.
  std::vector<FrameObservation> frame_observations;
  // The observations of survey frame `frame` (empty when it is not posed).
  std::span<const FrameObservation> observationsOfFrame(int frame) const;
  StepTimesMs total_ms{};   // per step, over all frames
  double wall_time_s = 0.0;
  double frames_per_second = 0.0;           // frames / wall time, decoding included
  // Frames per second of the tracking thread alone (track, detect, pnp,
  // triangulate, ba: the images already decoded and pre-processed).
  double trackingFramesPerSecond() const;
  double peak_memory_mb = 0.0;
  std::vector<std::string> warnings;  // undecodable frames, unlinked segments, ...
  // Whether the lamps' light was divided out before tracking, from how many
  // frames, and why not (lamp_light_field.h); empty when not run.
  std::string lamp_light_note;
  // How many frames were brought to the last frame's exposure before
  // tracking (gain steps, exposure_compensation.h); empty when switched off.
  std::string gain_note;

  int posedFrameCount() const;
  // One paragraph: frames posed, keyframes, landmarks, losses, speed.
  std::string summary() const;
};

}  // namespace hsmap
