#include "pipelines/evaluate/evaluation_metrics.h"

#include <cmath>
#include <cstdio>
#include <ostream>

#include "core/survey/number_text.h"

namespace hsmap {
namespace {

using M = EvaluationMetrics;

// JSON string: quotes, backslashes and control characters escaped (stage
// names come from run.yaml, which only refuses control characters).
std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", byte);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// Shortest round-trip number; a non-finite value (never expected) is null,
// since JSON has no NaN and a reader would reject the whole file.
std::string jsonNumber(double value) { return std::isfinite(value) ? formatDouble(value) : "null"; }

std::string jsonValue(const MetricValue& metric) {
  return metric.value ? jsonNumber(*metric.value) : "null";
}

// For people: six significant digits are more than any of these figures is worth.
std::string tableNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string tableValue(const MetricValue& metric) {
  return metric.value ? tableNumber(*metric.value) : "null";
}

std::string padded(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

constexpr std::size_t kKeyWidth = 40;  // the longest key, uhi_rotation_rmse_positions_aligned_deg, and a space
constexpr std::size_t kValueWidth = 14;
constexpr std::size_t kUnitWidth = 6;
constexpr std::size_t kFloorWidth = 14;

// The INS floor that goes beside a row, if any.
const MetricValue* floorBeside(const M& metrics, const std::string& key) {
  if (key == "rgb_ate_m") return &metrics.ins_floor_rgb_ate_m;
  if (key == "rgb_scale_error") return &metrics.ins_floor_scale_error;
  return nullptr;
}

bool isFloorRow(const std::string& key) { return key.rfind("ins_floor_", 0) == 0; }

// Extension rows the table shows right under the contract row they qualify
// (nullptr: in the file's order).
const char* shownUnder(const std::string& key) {
  if (key == "alignment_view_distance_m" || key == "uhi_position_rmse_positions_aligned_m" ||
      key == "uhi_rotation_rmse_positions_aligned_deg") {
    return "uhi_rotation_rmse_deg";
  }
  if (key == "alignment_cross_track_spread_m" || key == "mesh_accuracy_positions_aligned_m" ||
      key == "mesh_completeness_positions_aligned" || key == "mesh_accuracy_attitude_aligned_m" ||
      key == "mesh_completeness_attitude_aligned") {
    return "mesh_completeness";
  }
  return nullptr;
}

// A note on a row that has a value.
std::string noteOn(const M& metrics, const std::string& key) {
  if (key == "alignment_cross_track_spread_m" && metrics.alignment_cross_track_spread_m.value &&
      *metrics.alignment_cross_track_spread_m.value < kWeakRollCrossTrackSpreadM) {
    return "positions alone leave the roll about the track weakly determined";
  }
  return "";
}

std::string trimmedRight(std::string text) {
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

const std::vector<MetricRow>& metricRows() {
  static const std::vector<MetricRow> rows = {
      {"rgb_ate_m", "m", &M::rgb_ate_m},
      {"rgb_ate_aligned_m", "m", &M::rgb_ate_aligned_m},
      {"rgb_scale_error", "", &M::rgb_scale_error},
      {"uhi_position_rmse_m", "m", &M::uhi_position_rmse_m},
      {"uhi_rotation_rmse_deg", "deg", &M::uhi_rotation_rmse_deg},
      {"extrinsic_rotation_error_deg", "deg", &M::extrinsic_rotation_error_deg},
      {"extrinsic_translation_error_m", "m", &M::extrinsic_translation_error_m},
      {"time_offset_error_s", "s", &M::time_offset_error_s},
      {"mesh_accuracy_m", "m", &M::mesh_accuracy_m},
      {"mesh_completeness", "", &M::mesh_completeness},
      {"ortho_mean_shift_m", "m", &M::ortho_mean_shift_m},
      {"ortho_registration_rmse_m", "m", &M::ortho_registration_rmse_m},
      {"ortho_scale_error", "", &M::ortho_scale_error},
      {"ortho_sam_deg", "deg", &M::ortho_sam_deg},
      {"ortho_coverage", "", &M::ortho_coverage},
      {"ortho_pixel_error_m", "m", &M::ortho_pixel_error_m},
      {"ortho_pixel_error_abs_m", "m", &M::ortho_pixel_error_abs_m},
      {"reflectance_sam_deg", "deg", &M::reflectance_sam_deg},
      {"reflectance_rmse", "", &M::reflectance_rmse},
      {"reflectance_gain_free_rmse", "", &M::reflectance_gain_free_rmse},
      {"water_attenuation_rmse_per_m", "1/m", &M::water_attenuation_rmse_per_m},
      {"uhi_focal_error_rel", "", &M::uhi_focal_error_rel},
      {"uhi_cx_error_px", "px", &M::uhi_cx_error_px},
      {"rgb_focal_error_rel", "", &M::rgb_focal_error_rel},
      {"rgb_cx_error_px", "px", &M::rgb_cx_error_px},
      {"rgb_cy_error_px", "px", &M::rgb_cy_error_px},
      {"peak_rss_mb", "MiB", &M::peak_rss_mb},
      {"ins_floor_rgb_ate_m", "m", &M::ins_floor_rgb_ate_m},
      {"ins_floor_scale_error", "", &M::ins_floor_scale_error},
      {"alignment_cross_track_spread_m", "m", &M::alignment_cross_track_spread_m},
      {"mesh_accuracy_attitude_aligned_m", "m", &M::mesh_accuracy_attitude_aligned_m},
      {"mesh_completeness_attitude_aligned", "", &M::mesh_completeness_attitude_aligned},
      {"alignment_view_distance_m", "m", &M::alignment_view_distance_m},
      {"uhi_position_rmse_positions_aligned_m", "m", &M::uhi_position_rmse_positions_aligned_m},
      {"uhi_rotation_rmse_positions_aligned_deg", "deg", &M::uhi_rotation_rmse_positions_aligned_deg},
      {"mesh_accuracy_positions_aligned_m", "m", &M::mesh_accuracy_positions_aligned_m},
      {"mesh_completeness_positions_aligned", "", &M::mesh_completeness_positions_aligned},
  };
  return rows;
}

std::string metricsJson(const EvaluationMetrics& metrics) {
  std::string json = "{\n  \"variant\": " + jsonString(metrics.variant);
  for (const MetricRow& row : metricRows()) {
    if (std::string(row.key) == "peak_rss_mb") {
      json += ",\n  \"timings_s\": {";
      for (std::size_t i = 0; i < metrics.timings_s.size(); ++i) {
        json += (i > 0 ? ", " : "") + jsonString(metrics.timings_s[i].first) + ": " +
                jsonNumber(metrics.timings_s[i].second);
      }
      json += "}";
    }
    json += ",\n  \"" + std::string(row.key) + "\": " + jsonValue(metrics.*row.value);
    if (std::string(row.key) == "uhi_cx_error_px") {
      json += ",\n  \"uhi_distortion_error\": [" + jsonValue(metrics.uhi_distortion_error[0]) + ", " +
              jsonValue(metrics.uhi_distortion_error[1]) + "]";
    }
  }
  return json + "\n}\n";
}

void printMetricsTable(std::ostream& out, const EvaluationMetrics& metrics) {
  out << "variant: " << metrics.variant << "\n";
  out << trimmedRight(padded("metric", kKeyWidth) + padded("value", kValueWidth) +
                      padded("unit", kUnitWidth) + "INS floor")
      << "\n";
  const auto printRow = [&](const MetricRow& row) {
    const std::string key = row.key;
    const MetricValue& value = metrics.*row.value;
    std::string line = padded(key, kKeyWidth) + padded(tableValue(value), kValueWidth) +
                       padded(row.unit, kUnitWidth);
    std::string notes = value.value ? noteOn(metrics, key) : value.reason;
    if (const MetricValue* floor = floorBeside(metrics, key)) {
      line += padded(tableValue(*floor), kFloorWidth);
      if (!floor->value) notes += (notes.empty() ? "INS floor: " : "; INS floor: ") + floor->reason;
    } else if (!notes.empty()) {
      line += std::string(kFloorWidth, ' ');
    }
    out << trimmedRight(line + notes) << "\n";
  };
  for (const MetricRow& row : metricRows()) {
    const std::string key = row.key;
    if (isFloorRow(key)) continue;        // shown beside rgb_ate_m and rgb_scale_error
    if (shownUnder(key)) continue;        // shown under the row it qualifies
    if (key == "peak_rss_mb") {
      for (const auto& [stage, seconds] : metrics.timings_s) {
        out << trimmedRight(padded("timings_s." + stage, kKeyWidth) +
                            padded(tableNumber(seconds), kValueWidth) + "s")
            << "\n";
      }
    }
    printRow(row);
    if (key == "uhi_cx_error_px") {
      const auto& k = metrics.uhi_distortion_error;
      out << trimmedRight(padded("uhi_distortion_error", kKeyWidth) +
                          padded("[" + tableValue(k[0]) + ", " + tableValue(k[1]) + "]", kValueWidth) +
                          (k[0].value ? "" : k[0].reason))
          << "\n";
    }
    for (const MetricRow& under : metricRows()) {
      const char* parent = shownUnder(under.key);
      if (parent && key == parent) printRow(under);
    }
    if (key == "ortho_coverage" && !metrics.ortho_patches.empty()) {
      out << "  " << metrics.ortho_patches << "\n";
    }
    if (key == "ortho_pixel_error_abs_m" && !metrics.ortho_pixel_counts.empty()) {
      out << "  " << metrics.ortho_pixel_counts << "\n";
    }
  }
}

}  // namespace hsmap
