#pragma once
// Settings of the geo-referencing stage (docs/GEOREF.md says why each
// default is what it is).

#include "pipelines/frontend/frame_pose_estimator.h"
#include "pipelines/georef/georef_bundle_adjuster.h"

namespace hsmap {

struct GeorefOptions {
  GeorefBundleOptions bundle;
  PoseEstimatorOptions pose;
  // Two vision-posed frames further apart than this are a tracking gap,
  // bridged by the INS rather than interpolated (8 frames at 30 fps).
  double max_vision_gap_s = 0.27;
  // Window of the along-track heading when the INS has no attitude.
  double heading_window_s = 20.0;
};

}  // namespace hsmap
