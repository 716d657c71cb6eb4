#pragma once
// RgbAutoGain: the RGB camera's automatic gain control (rgb.auto_gain), as
// machine-vision and ROV cameras run it in continuous mode (GenICam SFNC
// `GainAuto = Continuous`): the camera meters the brightness of the frames it
// has taken and moves its analogue gain towards a target brightness, in the
// sensor's quantised gain steps, at a limited rate and with a dead band so
// that it does not hunt.
//
// Model. The gain g (dB) starts at initial_db. Every M = max(1,
// round(interval_s * rate_hz)) frames — after frame k with (k + 1) % M == 0 —
// the camera meters frame k: its mean DN over all pixels and channels, m. With
// the error e = 20 log10(target_dn / max(m, 0.5)) dB, if |e| > deadband_db the
// gain moves one step of step_db towards the target (clamped to [min_db,
// max_db]), and holds otherwise. The new gain applies from frame k + 1 (one
// frame of lag: the frame is metered after it is read out). So the gain
// changes only at frames that are multiples of M, by exactly step_db.
//
// A gain of g dB multiplies the signal by 10^(g / 20) (rgb_renderer.h says how
// it amplifies the noise). Frames in a dropout (rgb.blackouts) are not
// metered: the dropout is in the recording, not in the camera.
#include <cstdint>

namespace hsmap {

struct RgbAutoGainConfig {
  bool enabled = false;        // off: the fixed exposure (gain 0 dB)
  double target_dn = 100.0;    // the mean DN the camera aims for, in (0, 255)
  double step_db = 1.0;        // the size of one gain step, > 0
  double interval_s = 0.2;     // how often the camera may step, > 0
  double deadband_db = 1.0;    // no step while |error| <= this, >= 0
  double min_db = 0.0;         // gain range
  double max_db = 18.0;
  double initial_db = 0.0;     // in [min_db, max_db]
};

class RgbAutoGain {
 public:
  RgbAutoGain(const RgbAutoGainConfig& config, double rate_hz);

  // The gain (dB) of the next frame to be taken.
  double gainDb() const { return gain_db_; }
  // The linear factor of gainDb(): 10^(dB / 20); exactly 1 at 0 dB.
  double gain() const;
  // Frame `frame_index` has been taken with gainDb() and its mean DN is
  // `mean_dn`: steps the gain if the frame is one the camera meters.
  void meter(std::int64_t frame_index, double mean_dn);
  // Frames between the camera's gain decisions (M above).
  int meteringPeriodFrames() const { return period_frames_; }

 private:
  RgbAutoGainConfig config_;
  int period_frames_ = 1;
  double gain_db_ = 0.0;
};

}  // namespace hsmap
