#include "pipelines/hyperspectral/spectrum_validity.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

namespace hsmap {

void markInvalidSamples(const float* band_major, int bands, int samples, std::optional<float> ignore,
                        std::uint8_t* non_finite, std::uint8_t* ignored) {
  std::fill(non_finite, non_finite + samples, std::uint8_t(0));
  std::fill(ignored, ignored + samples, std::uint8_t(0));
  constexpr float kMax = std::numeric_limits<float>::max();
  for (int b = 0; b < bands; ++b) {
    const float* row = band_major + std::size_t(b) * std::size_t(samples);
    for (int s = 0; s < samples; ++s) non_finite[s] |= std::uint8_t(!(std::fabs(row[s]) <= kMax));
    if (ignore) {
      const float value = *ignore;
      for (int s = 0; s < samples; ++s) ignored[s] |= std::uint8_t(row[s] == value);
    }
  }
}

void requireCubeMatches(const std::string& who, const EnviReader& cube,
                        const std::vector<double>& wavelengths_nm, const PushbroomCamera& camera) {
  if (int(wavelengths_nm.size()) != cube.bands()) {
    throw std::invalid_argument(who + ": " + std::to_string(wavelengths_nm.size()) +
                                " wavelengths for a cube of " + std::to_string(cube.bands()) + " bands");
  }
  if (camera.samples() != cube.samples()) {
    throw std::invalid_argument(who + ": the UHI camera has " + std::to_string(camera.samples()) +
                                " samples, the cube " + std::to_string(cube.samples()));
  }
}

}  // namespace hsmap
