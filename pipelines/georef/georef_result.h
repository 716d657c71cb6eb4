#pragma once
// GeorefResult: what the geo-referencing stage produces for one variant:
// the pose of every RGB frame and every scan line in W, the landmarks in W
// (sequential), and what happened on the way (the INS alignment, the bundle
// adjustment's report, the fixes left out, where poses came from), as the
// run writes it into the results folder (georef_outputs.h) and prints it.

#include <optional>
#include <string>
#include <vector>

#include "core/geometry/se3.h"
#include "pipelines/frontend/visual_map.h"
#include "pipelines/georef/camera_trajectory.h"
#include "pipelines/georef/georef_bundle_adjuster.h"
#include "pipelines/georef/ins_alignment.h"
#include "pipelines/georef/map_placement.h"

namespace hsmap {

struct GeorefFramePose {
  int index = 0;     // survey frame index
  double t = 0.0;    // as in the survey's frames.csv
  SE3d T_W_C;
  PoseSource source = PoseSource::vision;
};

struct GeorefLinePose {
  long long line = 0;
  double t = 0.0;    // recorded time + the time offset used
  SE3d T_W_U;
  PoseSource source = PoseSource::vision;
};

// How the frames that vision posed were posed in W (sequential).
struct FrameReposeCounts {
  int keyframes = 0;       // from the bundle adjustment
  int pnp = 0;             // re-posed by PnP against the adjusted landmarks
  int from_keyframe = 0;   // PnP failed: carried along by their keyframe
};

struct GeorefResult {
  std::string variant;               // "sequential" or "planar"
  std::vector<GeorefFramePose> frames;
  std::vector<GeorefLinePose> lines;
  std::vector<Eigen::Vector3d> landmarks_W;
  // sequential: the adjusted map in W (keyframe poses T_W_C, landmarks p_W
  // and who sees them), for the surface stage.
  VisualMap map_W;
  SE3d T_C_U;                        // extrinsic used for the lines
  double time_offset_s = 0.0;        // d used for the lines
  // sequential with rgb.camera_sigma: the RGB intrinsics the bundle
  // adjustment estimated (written to calibration.yaml's rgb_camera, read
  // back by readGeorefOutputs; the later stages use them).
  std::optional<RgbIntrinsicsEstimate> rgb_camera;
  std::optional<InsAlignment> alignment;
  std::optional<GeorefBundleReport> bundle;
  // sequential: how well the INS places and scales the map (map_placement.h).
  std::optional<MapPlacement> placement;
  std::vector<RejectedFix> rejected_fixes;  // alignment and bundle adjustment
  FrameReposeCounts repose;
  std::vector<std::string> warnings;

  // Frames / lines per pose source.
  int frameCount(PoseSource source) const;
  int lineCount(PoseSource source) const;
  // A paragraph for people: alignment, solver report in words, fixes left
  // out (each with its ins.csv line), where the poses came from.
  std::string summary() const;
};

}  // namespace hsmap
