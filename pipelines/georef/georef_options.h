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
  // How long the INS's position errors stay correlated. A DVL-aided INS
  // wanders slowly between position resets, so fixes a second apart share
  // most of their error; weighting each as independent would let the INS's
  // wander bend the trajectory's shape (measured on transect-100m: 5.0 cm
  // RMS shape error with independent fixes, 2.5 cm with this weighting).
  // Each fix's position sigma is inflated by sqrt(correlation time / fix
  // interval) when that exceeds 1, so the fixes within one correlation time
  // count as one. 0 treats the fixes as independent.
  double ins_correlation_time_s = 10.0;
  // Window of the along-track heading when the INS has no attitude.
  double heading_window_s = 20.0;

  // std::invalid_argument naming the field and what was expected; the
  // geo-referencing functions call it.
  void validate() const;
};

}  // namespace hsmap
