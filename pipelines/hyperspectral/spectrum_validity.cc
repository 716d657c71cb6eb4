#include "pipelines/hyperspectral/spectrum_validity.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

namespace hsmap {

void markInvalidSamples(const float* pixel_major, int bands, int samples, std::optional<float> ignore,
                        std::uint8_t* non_finite, std::uint8_t* ignored) {
  constexpr float kMax = std::numeric_limits<float>::max();
  for (int s = 0; s < samples; ++s) {
    const float* spectrum = pixel_major + std::size_t(s) * std::size_t(bands);
    // Reductions without early exit, so the loops vectorise.
    bool bad = false;
    for (int b = 0; b < bands; ++b) bad |= !(std::fabs(spectrum[b]) <= kMax);
    bool skip = false;
    if (ignore) {
      const float value = *ignore;
      for (int b = 0; b < bands; ++b) skip |= spectrum[b] == value;
    }
    non_finite[s] = std::uint8_t(bad);
    ignored[s] = std::uint8_t(skip);
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
