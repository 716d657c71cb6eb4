#pragma once
// truth/rgb_gain.csv: the automatic gain of every RGB frame (rgb_auto_gain.h),
// written only when rgb.auto_gain is on. Columns `t,gain_db`: the frame's time
// (as in frames.csv) and its gain in dB over the fixed exposure (the signal
// is multiplied by 10^(gain_db / 20)).
#include <filesystem>
#include <vector>

namespace hsmap {

// Throws std::runtime_error when the file cannot be written.
void writeRgbGainTruth(const std::filesystem::path& file, const std::vector<double>& times,
                       const std::vector<double>& gains_db);

}  // namespace hsmap
