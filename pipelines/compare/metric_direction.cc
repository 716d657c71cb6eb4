#include "pipelines/compare/metric_direction.h"

#include <set>
#include <stdexcept>

namespace hsmap {

Better metricDirection(const std::string& key) {
  static const std::set<std::string> higher = {"mesh_completeness", "mesh_completeness_attitude_aligned",
                                               "mesh_completeness_positions_aligned", "ortho_coverage"};
  // Lower is better: every error the evaluation measures, and the run's cost.
  static const std::set<std::string> lower = {
      "rgb_ate_m", "rgb_ate_aligned_m", "rgb_scale_error", "uhi_position_rmse_m", "uhi_rotation_rmse_deg",
      "extrinsic_rotation_error_deg", "extrinsic_translation_error_m", "time_offset_error_s",
      "mesh_accuracy_m", "ortho_mean_shift_m", "ortho_registration_rmse_m", "ortho_scale_error",
      "ortho_sam_deg", "ortho_pixel_error_m", "ortho_pixel_error_abs_m", "reflectance_sam_deg",
      "reflectance_rmse", "reflectance_gain_free_rmse", "water_attenuation_rmse_per_m", "uhi_focal_error_rel",
      "uhi_cx_error_px", "rgb_focal_error_rel", "rgb_cx_error_px", "rgb_cy_error_px", "peak_rss_mb", "mesh_accuracy_attitude_aligned_m",
      "uhi_position_rmse_positions_aligned_m", "uhi_rotation_rmse_positions_aligned_deg",
      "mesh_accuracy_positions_aligned_m", "wall_time_s"};
  if (higher.contains(key)) return Better::higher;
  if (lower.contains(key) || key.starts_with("time_s.")) return Better::lower;
  return Better::none;
}

const char* toString(Better better) {
  switch (better) {
    case Better::lower: return "lower";
    case Better::higher: return "higher";
    case Better::none: break;
  }
  return "";
}

Better parseBetter(const std::string& text) {
  for (Better better : {Better::lower, Better::higher, Better::none}) {
    if (text == toString(better)) return better;
  }
  throw std::invalid_argument("expected lower, higher or nothing, got '" + text + "'");
}

}  // namespace hsmap
