#pragma once
// Local bundle adjustment on a sliding window of keyframes, with the engine.
//
// Variables: the poses of the window's keyframes (X(k)) and every valid
// landmark they observe (L(l)). Factors: every observation of those landmarks
// (ReprojectionFactor, distorted pixel, Huber loss) — also those made by
// keyframes outside the window, whose poses enter the problem held constant,
// as in ORB-SLAM's local mapping: they anchor the window to the older map so
// it cannot drift in position, orientation or scale. At most
// `max_fixed_keyframes` of them (the newest) are used, to bound the problem.
// When the window reaches back to its segment's first keyframes (no older
// keyframe sees it), the segment's first two keyframes are held constant
// instead: one pose fixes position and orientation, the second the scale.
//
// After the solve, every observation of the problem whose reprojection error
// exceeds `outlier_px` (or whose point is behind the camera) is removed from
// the map, and so is any landmark left with fewer than two observations:
// the robust loss let the solve ignore them, and the map must not keep them.

#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "pipelines/frontend/visual_map.h"

namespace hsmap {

struct LocalBundleAdjustmentOptions {
  double pixel_sigma_px = 1.0;
  double huber_scale = 2.0;
  int max_iterations = 5;
  int max_fixed_keyframes = 6;
  double outlier_px = 3.0;
  int solver_threads = 1;
};

struct LocalBundleAdjustmentReport {
  int free_keyframes = 0;
  int fixed_keyframes = 0;
  int landmarks = 0;
  int observations = 0;
  int removed_observations = 0;
  int removed_landmarks = 0;
  double initial_cost = 0.0;
  double final_cost = 0.0;
  bool usable = false;
};

// `window`: keyframe ids to optimise (all of one segment, in any order).
LocalBundleAdjustmentReport adjustLocalWindow(VisualMap& map, const std::vector<int>& window,
                                              const PinholeRadtanCamera& camera,
                                              const LocalBundleAdjustmentOptions& options);

// The same solve on given keyframes: `free_keyframes` adjusted, every
// landmark they observe with them, `fixed_keyframes` held constant (their
// observations of those landmarks enter the problem; other keyframes' do
// not). Used to adjust two segments joined by vision as one
// (segment_joiner.h): the new segment free, the earlier keyframes that see
// the merged landmarks fixed.
LocalBundleAdjustmentReport adjustKeyframes(VisualMap& map, const std::vector<int>& free_keyframes,
                                            const std::vector<int>& fixed_keyframes,
                                            const PinholeRadtanCamera& camera,
                                            const LocalBundleAdjustmentOptions& options);

// Removes observations (and landmarks left with < 2) of `landmark_ids` whose
// error exceeds outlier_px; returns {observations removed, landmarks removed}.
std::pair<int, int> removeOutlierObservations(VisualMap& map, const std::vector<int>& landmark_ids,
                                              const PinholeRadtanCamera& camera, double outlier_px);

}  // namespace hsmap
