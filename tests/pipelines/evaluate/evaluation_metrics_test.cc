// metrics.json and the table: every key of the contract, in its order, null
// where a metric is missing, numbers in shortest round-trip form.
#include "pipelines/evaluate/evaluation_metrics.h"

#include <gtest/gtest.h>

#include <sstream>

namespace hsmap {
namespace {

EvaluationMetrics example() {
  EvaluationMetrics metrics;
  metrics.variant = "joint";
  metrics.rgb_ate_m = MetricValue::of(0.1);
  metrics.rgb_ate_aligned_m = MetricValue::of(0.0123456789012345);
  metrics.rgb_scale_error = MetricValue::of(1e-7);
  metrics.uhi_position_rmse_m = MetricValue::of(0.02);
  metrics.uhi_rotation_rmse_deg = MetricValue::of(0.5);
  metrics.extrinsic_rotation_error_deg = MetricValue::of(0.25);
  metrics.extrinsic_translation_error_m = MetricValue::of(0.004);
  metrics.time_offset_error_s = MetricValue::of(0.0);
  const MetricValue no_mesh = MetricValue::missing("no surface stage");
  metrics.mesh_accuracy_m = no_mesh;
  metrics.mesh_completeness = no_mesh;
  const MetricValue no_ortho = MetricValue::missing("no products stage");
  metrics.ortho_mean_shift_m = no_ortho;
  metrics.ortho_registration_rmse_m = no_ortho;
  metrics.ortho_scale_error = no_ortho;
  metrics.ortho_sam_deg = no_ortho;
  metrics.ortho_coverage = no_ortho;
  metrics.ortho_pixel_error_m = no_ortho;
  metrics.ortho_pixel_error_abs_m = no_ortho;
  const MetricValue no_reflectance = MetricValue::missing("no reflectance product");
  metrics.reflectance_sam_deg = no_reflectance;
  metrics.reflectance_rmse = no_reflectance;
  metrics.reflectance_gain_free_rmse = no_reflectance;
  metrics.water_attenuation_rmse_per_m = no_reflectance;
  metrics.uhi_focal_error_rel = MetricValue::of(0.002);
  metrics.uhi_cx_error_px = MetricValue::of(0.5);
  metrics.uhi_distortion_error = {MetricValue::of(0.001), MetricValue::of(0.0002)};
  metrics.rgb_focal_error_rel = MetricValue::of(0.0004);
  metrics.rgb_cx_error_px = MetricValue::of(0.25);
  metrics.rgb_cy_error_px = MetricValue::missing("no RGB camera");
  metrics.timings_s = {{"frontend", 12.5}, {"geo \"ref\"", 3.25}, {"total", 15.75}};
  metrics.peak_rss_mb = MetricValue::of(300);
  metrics.ins_floor_rgb_ate_m = MetricValue::of(0.05);
  metrics.ins_floor_scale_error = MetricValue::missing("2 INS fix(es)");
  metrics.alignment_cross_track_spread_m = MetricValue::of(0.013);
  metrics.mesh_accuracy_attitude_aligned_m = no_mesh;
  metrics.mesh_completeness_attitude_aligned = no_mesh;
  metrics.alignment_view_distance_m = MetricValue::of(1.75);
  metrics.uhi_position_rmse_positions_aligned_m = MetricValue::of(0.03);
  metrics.uhi_rotation_rmse_positions_aligned_deg = MetricValue::of(0.9);
  metrics.mesh_accuracy_positions_aligned_m = no_mesh;
  metrics.mesh_completeness_positions_aligned = no_mesh;
  return metrics;
}

TEST(EvaluationMetrics, JsonHasEveryKeyInTheContractsOrder) {
  EXPECT_EQ(metricsJson(example()),
            "{\n"
            "  \"variant\": \"joint\",\n"
            "  \"rgb_ate_m\": 0.1,\n"
            "  \"rgb_ate_aligned_m\": 0.0123456789012345,\n"
            "  \"rgb_scale_error\": 1e-07,\n"
            "  \"uhi_position_rmse_m\": 0.02,\n"
            "  \"uhi_rotation_rmse_deg\": 0.5,\n"
            "  \"extrinsic_rotation_error_deg\": 0.25,\n"
            "  \"extrinsic_translation_error_m\": 0.004,\n"
            "  \"time_offset_error_s\": 0,\n"
            "  \"mesh_accuracy_m\": null,\n"
            "  \"mesh_completeness\": null,\n"
            "  \"ortho_mean_shift_m\": null,\n"
            "  \"ortho_registration_rmse_m\": null,\n"
            "  \"ortho_scale_error\": null,\n"
            "  \"ortho_sam_deg\": null,\n"
            "  \"ortho_coverage\": null,\n"
            "  \"ortho_pixel_error_m\": null,\n"
            "  \"ortho_pixel_error_abs_m\": null,\n"
            "  \"reflectance_sam_deg\": null,\n"
            "  \"reflectance_rmse\": null,\n"
            "  \"reflectance_gain_free_rmse\": null,\n"
            "  \"water_attenuation_rmse_per_m\": null,\n"
            "  \"uhi_focal_error_rel\": 0.002,\n"
            "  \"uhi_cx_error_px\": 0.5,\n"
            "  \"uhi_distortion_error\": [0.001, 2e-04],\n"
            "  \"rgb_focal_error_rel\": 4e-04,\n"
            "  \"rgb_cx_error_px\": 0.25,\n"
            "  \"rgb_cy_error_px\": null,\n"
            "  \"timings_s\": {\"frontend\": 12.5, \"geo \\\"ref\\\"\": 3.25, \"total\": 15.75},\n"
            "  \"peak_rss_mb\": 300,\n"
            "  \"ins_floor_rgb_ate_m\": 0.05,\n"
            "  \"ins_floor_scale_error\": null,\n"
            "  \"alignment_cross_track_spread_m\": 0.013,\n"
            "  \"mesh_accuracy_attitude_aligned_m\": null,\n"
            "  \"mesh_completeness_attitude_aligned\": null,\n"
            "  \"alignment_view_distance_m\": 1.75,\n"
            "  \"uhi_position_rmse_positions_aligned_m\": 0.03,\n"
            "  \"uhi_rotation_rmse_positions_aligned_deg\": 0.9,\n"
            "  \"mesh_accuracy_positions_aligned_m\": null,\n"
            "  \"mesh_completeness_positions_aligned\": null\n"
            "}\n");
}

TEST(EvaluationMetrics, TableShowsValuesUnitsTheInsFloorAndWhyAValueIsMissing) {
  std::ostringstream out;
  printMetricsTable(out, example());
  EXPECT_EQ(out.str(),
            "variant: joint\n"
            "metric                                  value         unit  INS floor\n"
            "rgb_ate_m                               0.1           m     0.05\n"
            "rgb_ate_aligned_m                       0.0123457     m\n"
            "rgb_scale_error                         1e-07               null          INS floor: 2 INS fix(es)\n"
            "uhi_position_rmse_m                     0.02          m\n"
            "uhi_rotation_rmse_deg                   0.5           deg\n"
            "alignment_view_distance_m               1.75          m\n"
            "uhi_position_rmse_positions_aligned_m   0.03          m\n"
            "uhi_rotation_rmse_positions_aligned_deg 0.9           deg\n"
            "extrinsic_rotation_error_deg            0.25          deg\n"
            "extrinsic_translation_error_m           0.004         m\n"
            "time_offset_error_s                     0             s\n"
            "mesh_accuracy_m                         null          m                   no surface stage\n"
            "mesh_completeness                       null                              no surface stage\n"
            "alignment_cross_track_spread_m          0.013         m                   positions alone leave the roll about the track weakly determined\n"
            "mesh_accuracy_attitude_aligned_m        null          m                   no surface stage\n"
            "mesh_completeness_attitude_aligned      null                              no surface stage\n"
            "mesh_accuracy_positions_aligned_m       null          m                   no surface stage\n"
            "mesh_completeness_positions_aligned     null                              no surface stage\n"
            "ortho_mean_shift_m                      null          m                   no products stage\n"
            "ortho_registration_rmse_m               null          m                   no products stage\n"
            "ortho_scale_error                       null                              no products stage\n"
            "ortho_sam_deg                           null          deg                 no products stage\n"
            "ortho_coverage                          null                              no products stage\n"
            "ortho_pixel_error_m                     null          m                   no products stage\n"
            "ortho_pixel_error_abs_m                 null          m                   no products stage\n"
            "reflectance_sam_deg                     null          deg                 no reflectance product\n"
            "reflectance_rmse                        null                              no reflectance product\n"
            "reflectance_gain_free_rmse              null                              no reflectance product\n"
            "water_attenuation_rmse_per_m            null          1/m                 no reflectance product\n"
            "uhi_focal_error_rel                     0.002\n"
            "uhi_cx_error_px                         0.5           px\n"
            "uhi_distortion_error                    [0.001, 0.0002]\n"
            "rgb_focal_error_rel                     0.0004\n"
            "rgb_cx_error_px                         0.25          px\n"
            "rgb_cy_error_px                         null          px                  no RGB camera\n"
            "timings_s.frontend                      12.5          s\n"
            "timings_s.geo \"ref\"                     3.25          s\n"
            "timings_s.total                         15.75         s\n"
            "peak_rss_mb                             300           MiB\n");
}

TEST(EvaluationMetrics, TableShowsTheOrthoPatchCountsAndNoNoteForAWideTrack) {
  EvaluationMetrics metrics = example();
  metrics.alignment_cross_track_spread_m = MetricValue::of(0.4);
  metrics.mesh_accuracy_attitude_aligned_m = MetricValue::of(0.002);
  metrics.mesh_completeness_attitude_aligned = MetricValue::of(0.95);
  metrics.ortho_coverage = MetricValue::of(0.9);
  metrics.ortho_patches = "ortho: 24 patches of 60 px, 24 with data, 23 matched";
  metrics.ortho_pixel_error_m = MetricValue::of(0.004);
  metrics.ortho_pixel_error_abs_m = MetricValue::of(0.05);
  metrics.ortho_pixel_counts = "ortho pixels: 9000 name a scan line and sample";
  std::ostringstream out;
  printMetricsTable(out, metrics);
  const std::string table = out.str();
  EXPECT_NE(table.find("alignment_cross_track_spread_m          0.4           m\n"), std::string::npos)
      << table;
  EXPECT_NE(table.find("mesh_accuracy_attitude_aligned_m        0.002         m\n"
                       "mesh_completeness_attitude_aligned      0.95\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("ortho_coverage                          0.9\n"
                       "  ortho: 24 patches of 60 px, 24 with data, 23 matched\n"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("ortho_pixel_error_abs_m                 0.05          m\n"
                       "  ortho pixels: 9000 name a scan line and sample\n"),
            std::string::npos)
      << table;
  // The counts are for people: not keys of the file.
  EXPECT_EQ(metricsJson(metrics).find("patches"), std::string::npos);
  EXPECT_EQ(metricsJson(metrics).find("ortho pixels"), std::string::npos);
}

}  // namespace
}  // namespace hsmap
