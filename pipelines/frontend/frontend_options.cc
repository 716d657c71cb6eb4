#include "pipelines/frontend/frontend_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

namespace {

[[noreturn]] void invalid(const char* field, double value, const char* expected) {
  std::ostringstream message;
  message << "FrontendOptions." << field << " must be " << expected << ", got " << value;
  throw std::invalid_argument(message.str());
}

void positive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0)) invalid(field, value, "a finite number > 0");
}

void atLeast(const char* field, int value, int minimum) {
  if (value < minimum) {
    invalid(field, value, (">= " + std::to_string(minimum)).c_str());
  }
}

void fraction(const char* field, double value) {
  if (!(value >= 0.0 && value <= 1.0)) invalid(field, value, "in [0, 1]");
}

void angle(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0.0 && value < 90.0)) {
    invalid(field, value, "an angle in (0, 90) degrees");
  }
}

}  // namespace

void FrontendOptions::validate() const {
  positive("reference_width_px", reference_width_px);
  positive("clahe_clip_limit", clahe_clip_limit);
  atLeast("clahe_tiles_across", clahe_tiles_across, 1);
  atLeast("lamp_light_frames", lamp_light_frames, 1);
  atLeast("lamp_light_min_frames", lamp_light_min_frames, 1);
  positive("lamp_light_blur_px", lamp_light_blur_px);
  if (!(min_contrast_dn >= 0.0 && std::isfinite(min_contrast_dn))) {
    invalid("min_contrast_dn", min_contrast_dn, "a finite number >= 0");
  }
  fraction("max_saturated_fraction", max_saturated_fraction);
  if (!(gain_compensation_min_db >= 0.0 && std::isfinite(gain_compensation_min_db))) {
    invalid("gain_compensation_min_db", gain_compensation_min_db, "a finite number >= 0");
  }
  atLeast("min_corners", min_corners, 8);
  atLeast("klt_window_px", klt_window_px, 5);
  atLeast("klt_pyramid_levels", klt_pyramid_levels, 0);
  atLeast("klt_max_iterations", klt_max_iterations, 1);
  positive("klt_epsilon", klt_epsilon);
  positive("forward_backward_max_px", forward_backward_max_px);
  atLeast("grid_cells_across", grid_cells_across, 1);
  atLeast("max_corners_per_cell", max_corners_per_cell, 1);
  positive("min_corner_distance_px", min_corner_distance_px);
  if (!(corner_quality > 0.0 && corner_quality < 1.0)) {
    invalid("corner_quality", corner_quality, "in (0, 1)");
  }
  atLeast("init_min_tracks", init_min_tracks, 8);
  angle("init_min_parallax_deg", init_min_parallax_deg);
  atLeast("init_min_landmarks", init_min_landmarks, 8);
  fraction("init_min_cheirality_fraction", init_min_cheirality_fraction);
  atLeast("init_max_reference_age", init_max_reference_age, 2);
  positive("ransac_threshold_px", ransac_threshold_px);
  positive("pnp_threshold_px", pnp_threshold_px);
  atLeast("pnp_ransac_iterations", pnp_ransac_iterations, 1);
  atLeast("min_pose_inliers", min_pose_inliers, 6);
  positive("pixel_sigma_px", pixel_sigma_px);
  positive("huber_scale", huber_scale);
  atLeast("refine_max_iterations", refine_max_iterations, 1);
  positive("inlier_threshold_px", inlier_threshold_px);
  angle("keyframe_parallax_deg", keyframe_parallax_deg);
  fraction("keyframe_min_tracked_fraction", keyframe_min_tracked_fraction);
  fraction("keyframe_min_coverage", keyframe_min_coverage);
  atLeast("keyframe_min_interval", keyframe_min_interval, 1);
  angle("min_triangulation_angle_deg", min_triangulation_angle_deg);
  positive("max_triangulation_error_px", max_triangulation_error_px);
  atLeast("ba_window_keyframes", ba_window_keyframes, 2);
  atLeast("ba_max_fixed_keyframes", ba_max_fixed_keyframes, 1);
  atLeast("ba_max_iterations", ba_max_iterations, 1);
  atLeast("ba_every_keyframes", ba_every_keyframes, 1);
  positive("ba_outlier_px", ba_outlier_px);
  atLeast("max_bridged_frames", max_bridged_frames, 0);
  atLeast("min_tracked_points", min_tracked_points, 6);
  atLeast("min_segment_keyframes", min_segment_keyframes, 3);
  atLeast("join_min_inliers", join_min_inliers, 6);
  positive("max_ins_scale_sigma", max_ins_scale_sigma);
  atLeast("prefetch_frames", prefetch_frames, 1);
  atLeast("solver_threads", solver_threads, 1);
  atLeast("first_frame", first_frame, 0);
  if (last_frame != -1 && last_frame < first_frame) {
    invalid("last_frame", last_frame, "-1 (to the end) or >= first_frame");
  }
}

double FrontendOptions::errorScale(int width_px) const {
  return std::max(1.0, width_px / reference_width_px);
}

}  // namespace hsmap
