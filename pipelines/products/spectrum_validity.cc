#include "pipelines/products/spectrum_validity.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>

namespace hsmap {

void markInvalidSamples(const float* pixel_major, int bands, int samples, EnviDataType stored,
                        std::optional<float> ignore, std::uint8_t* non_finite, std::uint8_t* ignored) {
  constexpr float kMax = std::numeric_limits<float>::max();
  const bool can_be_non_finite = stored == EnviDataType::float32 || stored == EnviDataType::float64;
  std::fill(non_finite, non_finite + samples, std::uint8_t(0));
  std::fill(ignored, ignored + samples, std::uint8_t(0));
  if (!can_be_non_finite && !ignore) return;
  for (int s = 0; s < samples; ++s) {
    const float* spectrum = pixel_major + std::size_t(s) * std::size_t(bands);
    // Reductions without early exit, so the loops vectorise.
    if (can_be_non_finite) {
      bool bad = false;
      for (int b = 0; b < bands; ++b) bad |= !(std::fabs(spectrum[b]) <= kMax);
      non_finite[s] = std::uint8_t(bad);
    }
    if (ignore) {
      const float value = *ignore;
      bool skip = false;
      for (int b = 0; b < bands; ++b) skip |= spectrum[b] == value;
      ignored[s] = std::uint8_t(skip);
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
