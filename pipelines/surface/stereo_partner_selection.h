#pragma once
// Which keyframe each keyframe is matched with for its dense depth map
// (docs/SURFACE.md, "Dense points"), chosen from the adjusted sparse map
// alone, before any image is read.
//
// A good partner j for keyframe k sees much of what k sees (shared
// landmarks), looks the same way (the rectified pair stays close to the
// original images), and is at a baseline B giving depth precision without
// too much perspective change: B / Z near `target_baseline_ratio`, with Z
// the median depth of k's landmarks. At Z = 2 m, f = 800 px and a
// disparity error of 0.2 px, B / Z = 0.2 gives 2.5 mm of depth noise per
// pixel while the neighbour still covers most of k's image when it
// moves along the track. The depth range searched is that of k's
// landmarks, widened by `depth_margin`.

#include <optional>
#include <string>
#include <vector>

#include "pipelines/frontend/visual_map.h"

namespace hsmap {

struct StereoPartnerOptions {
  double target_baseline_ratio = 0.2;  // B / Z sought
  double min_baseline_ratio = 0.06;    // below: depth too noisy
  double max_baseline_ratio = 0.5;     // above: too little overlap, too much perspective change
  double max_axis_angle_deg = 20.0;    // between the two optical axes
  double min_shared_fraction = 0.25;   // of k's landmarks also seen by the partner
  int min_landmarks = 20;              // k needs this many landmarks for a depth range
  double depth_margin = 0.15;          // the range [p05 (1 - m), p95 (1 + m)]

  std::string validate() const;
};

struct StereoPartner {
  int keyframe = -1;
  int partner = -1;
  double baseline_m = 0.0;
  double median_depth_m = 0.0;
  double min_depth_m = 0.0;   // depth range to search, in k's camera
  double max_depth_m = 0.0;
};

// One entry per keyframe of `map_W` (T_F_C are poses in W): its partner, or
// nullopt when no keyframe qualifies (too few landmarks, no neighbour at a
// usable baseline). Throws std::invalid_argument for invalid options.
std::vector<std::optional<StereoPartner>> selectStereoPartners(const VisualMap& map_W,
                                                               const StereoPartnerOptions& options);

}  // namespace hsmap
