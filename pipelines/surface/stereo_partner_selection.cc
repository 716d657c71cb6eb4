#include "pipelines/surface/stereo_partner_selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace hsmap {
namespace {

double quantile(std::vector<double> values, double q) {
  const std::size_t i = std::min(values.size() - 1, std::size_t(q * double(values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(i), values.end());
  return values[i];
}

}  // namespace

std::string StereoPartnerOptions::validate() const {
  if (!(min_baseline_ratio > 0.0 && min_baseline_ratio <= target_baseline_ratio &&
        target_baseline_ratio <= max_baseline_ratio)) {
    return "stereo baseline ratios must satisfy 0 < min <= target <= max";
  }
  if (!(max_axis_angle_deg > 0.0 && max_axis_angle_deg < 90.0)) {
    return "max_axis_angle_deg must be in (0, 90)";
  }
  if (!(min_shared_fraction >= 0.0 && min_shared_fraction <= 1.0)) {
    return "min_shared_fraction must be in [0, 1]";
  }
  if (min_landmarks < 3) return "min_landmarks must be at least 3";
  if (!(depth_margin >= 0.0 && depth_margin < 1.0)) return "depth_margin must be in [0, 1)";
  return {};
}

std::vector<std::optional<StereoPartner>> selectStereoPartners(const VisualMap& map_W,
                                                               const StereoPartnerOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty()) {
    throw std::invalid_argument(problem);
  }
  const auto& keyframes = map_W.keyframes();
  std::vector<std::optional<StereoPartner>> partners(keyframes.size());
  const double cos_max_angle = std::cos(options.max_axis_angle_deg * M_PI / 180.0);
  for (const Keyframe& k : keyframes) {
    const SE3d T_C_W = k.T_F_C.inverse();
    std::vector<double> depths;
    std::unordered_map<int, int> shared;  // partner keyframe -> landmarks seen by both
    for (const KeyframeObservation& observation : k.observations) {
      const Landmark& landmark = map_W.landmark(observation.landmark_id);
      if (!landmark.valid) continue;
      const double z = (T_C_W * landmark.p_F).z();
      if (!(z > 0.0)) continue;
      depths.push_back(z);
      for (int other : landmark.keyframe_ids) {
        if (other != k.id) ++shared[other];
      }
    }
    if (int(depths.size()) < options.min_landmarks) continue;
    StereoPartner best;
    best.keyframe = k.id;
    best.median_depth_m = quantile(depths, 0.5);
    best.min_depth_m = quantile(depths, 0.05) * (1.0 - options.depth_margin);
    best.max_depth_m = quantile(depths, 0.95) * (1.0 + options.depth_margin);
    const Eigen::Vector3d axis_k = k.T_F_C.q * Eigen::Vector3d::UnitZ();
    double best_score = 0.0;
    for (const auto& [j, count] : shared) {
      if (double(count) < options.min_shared_fraction * double(depths.size())) continue;
      const Keyframe& candidate = map_W.keyframe(j);
      const double baseline = (candidate.T_F_C.t - k.T_F_C.t).norm();
      const double ratio = baseline / best.median_depth_m;
      if (ratio < options.min_baseline_ratio || ratio > options.max_baseline_ratio) continue;
      if (axis_k.dot(candidate.T_F_C.q * Eigen::Vector3d::UnitZ()) < cos_max_angle) continue;
      // Closest to the target ratio on a log scale, ties to the more shared.
      const double score = std::abs(std::log(ratio / options.target_baseline_ratio)) -
                           1e-6 * double(count);
      if (best.partner < 0 || score < best_score) {
        best.partner = j;
        best.baseline_m = baseline;
        best_score = score;
      }
    }
    if (best.partner >= 0) partners[std::size_t(k.id)] = best;
  }
  return partners;
}

}  // namespace hsmap
