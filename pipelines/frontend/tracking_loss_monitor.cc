#include "pipelines/frontend/tracking_loss_monitor.h"

#include <cstdio>

namespace hsmap {

std::optional<std::string> textureProblem(const ImageQuality& quality, const FrontendOptions& options) {
  char text[128];
  if (quality.saturated_fraction > options.max_saturated_fraction) {
    std::snprintf(text, sizeof(text), "no texture: over-exposed (%.0f %% of pixels saturated)",
                  100.0 * quality.saturated_fraction);
    return std::string(text);
  }
  if (quality.contrast_dn < options.min_contrast_dn) {
    // Dark and flat are the same failure (nothing to track); the mean tells
    // a user which one to look for.
    std::snprintf(text, sizeof(text), "no texture: %s (mean %.1f DN, contrast %.1f DN)",
                  quality.mean_dn < 20.0 ? "dark" : "flat", quality.mean_dn, quality.contrast_dn);
    return std::string(text);
  }
  return std::nullopt;
}

std::vector<TrackingLoss> collectLosses(const std::vector<FrameRecord>& frames,
                                        const std::map<int, std::string>& reasons) {
  std::vector<TrackingLoss> losses;
  std::size_t i = 0;
  while (i < frames.size()) {
    if (frames[i].posed) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < frames.size() && !frames[j + 1].posed) ++j;
    TrackingLoss loss;
    loss.first_frame = frames[i].index;
    loss.last_frame = frames[j].index;
    loss.reason = "not posed";
    for (std::size_t k = i; k <= j; ++k) {
      const auto it = reasons.find(frames[k].index);
      if (it != reasons.end()) {
        loss.reason = it->second;
        break;
      }
    }
    losses.push_back(loss);
    i = j + 1;
  }
  return losses;
}

}  // namespace hsmap
