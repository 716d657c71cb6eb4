#include "pipelines/simulate/rgb_auto_gain.h"

#include <algorithm>
#include <cmath>

namespace hsmap {

RgbAutoGain::RgbAutoGain(const RgbAutoGainConfig& config, double rate_hz)
    : config_(config),
      period_frames_(std::max(1, int(std::lround(config.interval_s * rate_hz)))),
      gain_db_(config.enabled ? config.initial_db : 0.0) {}

double RgbAutoGain::gain() const {
  return gain_db_ == 0.0 ? 1.0 : std::pow(10.0, gain_db_ / 20.0);
}

void RgbAutoGain::meter(std::int64_t frame_index, double mean_dn) {
  if (!config_.enabled || (frame_index + 1) % period_frames_ != 0) return;
  const double error_db = 20.0 * std::log10(config_.target_dn / std::max(mean_dn, 0.5));
  if (std::abs(error_db) <= config_.deadband_db) return;
  const double step = error_db > 0.0 ? config_.step_db : -config_.step_db;
  gain_db_ = std::clamp(gain_db_ + step, config_.min_db, config_.max_db);
}

}  // namespace hsmap
