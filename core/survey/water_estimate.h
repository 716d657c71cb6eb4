#pragma once
// WaterEstimate: what the radiometry stage estimated (docs/RADIOMETRY.md),
// as RUN/radiometry/water.yaml and as the `water:` block of the run's
// calibration.yaml (shared/DATASET.md, "Results folder"):
//
//   water:
//     attenuation_per_m: [c_1, ..., c_bands]      c(λ) per UHI band, 1/m
//     attenuation_sigma_per_m: [s_1, ..., s_bands] 1-sigma (null: undetermined)
//     backscatter_dn: [b_1, ..., b_bands]         zeros when not estimated
//     backscatter_sigma_dn: [...]                 1-sigma (null: not estimated)
//     beam: {model: exp-even-polynomial, coefficients: [m_1, m_2],
//            coefficients_sigma: [s_1, s_2]}      B(θ) = exp(m_1 θ² + m_2 θ⁴), θ in radians
//   warnings: [...]                               what the survey cannot determine
//
// RUN/radiometry/water.yaml holds `format: hsmap-water/1`, the `water` map
// and `warnings`. Reading is strict: a missing or unknown key, a list of the
// wrong length or a non-number is an InputError naming the file, line and
// key. The beam model is documented in factors/lamp_radiance_factor.h.

#include <yaml-cpp/yaml.h>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace hsmap {

struct WaterEstimate {
  static constexpr const char* kFormat = "hsmap-water/1";
  static constexpr const char* kBeamModel = "exp-even-polynomial";
  std::vector<double> attenuation_per_m;
  std::vector<std::optional<double>> attenuation_sigma_per_m;
  std::vector<double> backscatter_dn;
  std::vector<std::optional<double>> backscatter_sigma_dn;
  std::array<double, 2> beam{0.0, 0.0};
  std::array<std::optional<double>, 2> beam_sigma;
  std::vector<std::string> warnings;

  int bands() const { return int(attenuation_per_m.size()); }
};

// The value of the `water` key (a block map) into the map `out` is in.
void emitWaterBlock(YAML::Emitter& out, const WaterEstimate& water);
// The `water` map found at `node` (dotted key `key`, e.g. "water") of `file`.
WaterEstimate readWaterBlock(const std::filesystem::path& file, const YAML::Node& node, const std::string& key);
// RUN/radiometry/water.yaml, atomically.
void writeWaterEstimate(const std::filesystem::path& file, const WaterEstimate& water);
// Reads it back; InputError naming the file, line and key.
WaterEstimate readWaterEstimate(const std::filesystem::path& file);

}  // namespace hsmap
