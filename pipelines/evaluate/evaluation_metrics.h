#pragma once
// EvaluationMetrics: the figures of RUN/metrics.json (DATASET.md's keys, in
// its order, plus hsmap's extensions: the INS floor, the attitude-aligned
// mesh metrics, the frames' cross-track spread, the view distance of the
// view Sim(3) and the positions-aligned uhi and mesh metrics), and their two
// renderings:
//   - metricsJson(): the file. Every key present, `null` where a metric does
//     not apply, numbers in shortest round-trip form (number_text.h), so a
//     script reads back exactly what was computed;
//   - printMetricsTable(): the same figures for people: metric, value, unit,
//     the INS floor beside rgb_ate_m and rgb_scale_error, the view distance
//     and the positions-aligned uhi rows under the uhi rows, the
//     positions- and attitude-aligned mesh rows and the cross-track spread
//     under the mesh rows (with a note when the spread leaves the positions
//     weakly conditioned), the ortho-image's patch counts under its rows and
//     the pixel error's counts under its own, and the reason of every
//     missing value.
//
// metricRows() lists the scalar metrics once, so the file, the table and any
// later metric cannot disagree on keys, order or units.

#include <iosfwd>
#include <string>
#include <utility>
#include <array>
#include <vector>

#include "pipelines/evaluate/metric_value.h"

#include "pipelines/evaluate/ortho_metrics.h"

namespace hsmap {

struct EvaluationMetrics {
  std::string variant;  // from run.yaml
  MetricValue rgb_ate_m;
  MetricValue rgb_ate_aligned_m;
  MetricValue rgb_scale_error;
  MetricValue uhi_position_rmse_m;
  MetricValue uhi_rotation_rmse_deg;
  MetricValue extrinsic_rotation_error_deg;
  MetricValue extrinsic_translation_error_m;
  MetricValue time_offset_error_s;
  // Surface metrics (mesh_metrics.h): measured when the run has RUN/map/mesh.ply.
  MetricValue mesh_accuracy_m;
  MetricValue mesh_completeness;
  // Ortho-image metrics (ortho_metrics.h): measured when the run has
  // RUN/hyperspectral/ortho.hdr.
  MetricValue ortho_mean_shift_m;
  MetricValue ortho_registration_rmse_m;
  MetricValue ortho_scale_error;
  MetricValue ortho_sam_deg;
  MetricValue ortho_coverage;
  // Matching-free pixel error (ortho_pixel_error.h): measured when the run
  // has RUN/hyperspectral/ortho.hdr and its ancillary layer.
  MetricValue ortho_pixel_error_m;
  MetricValue ortho_pixel_error_abs_m;
  // Reflectance (the contract's keys): hsmap makes no reflectance product
  // yet, so they are null with that reason.
  MetricValue reflectance_sam_deg;
  MetricValue reflectance_rmse;
  MetricValue reflectance_gain_free_rmse;
  MetricValue water_attenuation_rmse_per_m;
  // The UHI camera's intrinsics against the truth (calibration_metrics.h);
  // uhi_distortion_error is metrics.json's list [k1, k2].
  MetricValue uhi_focal_error_rel;
  MetricValue uhi_cx_error_px;
  std::array<MetricValue, 2> uhi_distortion_error;
  // The RGB camera's intrinsics against the truth (calibration_metrics.h;
  // not named by the contract: hsmap's keys, in the UHI ones' style).
  MetricValue rgb_focal_error_rel;
  MetricValue rgb_cx_error_px;
  MetricValue rgb_cy_error_px;
  // For the table only (not in metrics.json): the pixel error's counts
  // (OrthoPixelError::summary()), empty when it was not measured.
  std::string ortho_pixel_counts;
  // For the table only (not in metrics.json): the ortho-image's patch counts
  // (OrthoMetrics::summary()'s first line), empty when it was not measured.
  std::string ortho_patches;
  // Not in metrics.json: every matched patch (evaluateRunFolder writes them
  // to RUN/report/ortho_patches.csv).
  std::vector<OrthoPatchMatch> ortho_matches;
  // Stage name -> wall time (s), in the order the stages ran, then "total".
  std::vector<std::pair<std::string, double>> timings_s;
  MetricValue peak_rss_mb;
  // Extension (docs/EVALUATE.md, "INS floor"): what the INS alone allows.
  MetricValue ins_floor_rgb_ate_m;
  MetricValue ins_floor_scale_error;
  // Extension (docs/EVALUATE.md, "The attitude-aligned mesh metrics"): the
  // std of the true frame positions across the track's main direction, and
  // the mesh metrics with the mesh mapped by the attitude-anchored alignment
  // (trajectory_metrics.h).
  MetricValue alignment_cross_track_spread_m;
  MetricValue mesh_accuracy_attitude_aligned_m;
  MetricValue mesh_completeness_attitude_aligned;
  // Extension (docs/EVALUATE.md, "The view Sim(3)"): the view distance h of
  // the frames' view Sim(3), and the uhi and mesh metrics under the frame
  // positions' Umeyama alignment (that of rgb_ate_aligned_m) instead.
  MetricValue alignment_view_distance_m;
  MetricValue uhi_position_rmse_positions_aligned_m;
  MetricValue uhi_rotation_rmse_positions_aligned_deg;
  MetricValue mesh_accuracy_positions_aligned_m;
  MetricValue mesh_completeness_positions_aligned;
};

// Below this cross-track spread of the frames (m) the table says that the
// positions alone leave the roll about the track weakly determined: with
// millimetres of position error over hundreds of frames, Umeyama's roll is
// then off by ~0.1 degree or more, millimetres at a seabed a metre aside.
inline constexpr double kWeakRollCrossTrackSpreadM = 0.05;

// One scalar metric: its JSON key, unit ("m", "deg", "s", "MiB", "" for a
// ratio) and where it lives.
struct MetricRow {
  const char* key;
  const char* unit;
  MetricValue EvaluationMetrics::*value;
};
// In metrics.json's order; timings_s goes between ortho_coverage and
// peak_rss_mb; the extensions follow peak_rss_mb.
const std::vector<MetricRow>& metricRows();

std::string metricsJson(const EvaluationMetrics& metrics);
void printMetricsTable(std::ostream& out, const EvaluationMetrics& metrics);

}  // namespace hsmap
