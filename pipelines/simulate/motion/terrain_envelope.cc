#include "pipelines/simulate/motion/terrain_envelope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/survey/number_text.h"

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("TerrainEnvelopeOptions: " + what);
}

}  // namespace

void TerrainEnvelopeOptions::validate() const {
  if (!(radius_m > 0.0) || !std::isfinite(radius_m)) {
    fail("radius_m must be a finite number > 0, got " + formatDouble(radius_m));
  }
  if (!(smoothing_half_width_m > 0.0) || !(smoothing_half_width_m <= radius_m)) {
    fail("smoothing_half_width_m must be in (0, radius_m], got " +
         formatDouble(smoothing_half_width_m));
  }
  if (cross_samples < 1) fail("cross_samples must be >= 1, got " + std::to_string(cross_samples));
  if (!(min_spacing_m > 0.0) || !std::isfinite(min_spacing_m)) {
    fail("min_spacing_m must be a finite number > 0, got " + formatDouble(min_spacing_m));
  }
  if (max_queries < 2 * cross_samples) {
    fail("max_queries must be >= 2 * cross_samples, got " + std::to_string(max_queries));
  }
}

TerrainEnvelope::TerrainEnvelope(const LanePath& path,
                                 const std::function<double(double, double)>& seabed_z,
                                 const TerrainEnvelopeOptions& options)
    : spline_(build(path, seabed_z, options, &queries_)) {}

NaturalCubicSpline TerrainEnvelope::build(const LanePath& path,
                                          const std::function<double(double, double)>& seabed_z,
                                          const TerrainEnvelopeOptions& options, int* queries) {
  options.validate();
  if (!seabed_z) throw std::invalid_argument("TerrainEnvelope: seabed_z is empty");
  const double length = path.length();
  // Sample count along track: as fine as min_spacing_m allows within the budget.
  const long long by_spacing = static_cast<long long>(std::floor(length / options.min_spacing_m)) + 1;
  const long long by_budget = options.max_queries / options.cross_samples;
  const std::size_t count = static_cast<std::size_t>(std::max(2LL, std::min(by_spacing, by_budget)));
  const double ds = length / static_cast<double>(count - 1);
  const double intervals = static_cast<double>(count - 1);

  // 1. Highest (smallest z) finite sample across track at each s_i.
  constexpr double kNone = std::numeric_limits<double>::infinity();
  std::vector<double> s(count);
  std::vector<double> across_min(count, kNone);
  *queries = 0;
  for (std::size_t i = 0; i < count; ++i) {
    // length * i / (count - 1): exact at both ends, no accumulated rounding.
    s[i] = length * static_cast<double>(i) / intervals;
    const PathPoint point = path.at(s[i]);
    // Starboard (right of the direction of travel) in NED: heading + 90 degrees.
    const double right_north = -std::sin(point.heading_rad);
    const double right_east = std::cos(point.heading_rad);
    for (int k = 0; k < options.cross_samples; ++k) {
      const double offset =
          options.cross_samples == 1
              ? 0.0
              : options.radius_m * (2.0 * k / (options.cross_samples - 1) - 1.0);
      const double z = seabed_z(point.north_m + offset * right_north,
                                point.east_m + offset * right_east);
      ++*queries;
      if (std::isfinite(z)) across_min[i] = std::min(across_min[i], z);
    }
  }

  // 2. Upper envelope along track (window of +-radius). A small epsilon keeps
  // samples exactly at the radius inside the window despite rounding.
  const auto reach = [&](double half_width) {
    return static_cast<std::size_t>(std::floor(half_width / ds + 1e-9));
  };
  const std::size_t envelope_reach = reach(options.radius_m);
  std::vector<double> envelope(count, kNone);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t first = i >= envelope_reach ? i - envelope_reach : 0;
    const std::size_t last = std::min(count - 1, i + envelope_reach);
    for (std::size_t j = first; j <= last; ++j) envelope[i] = std::min(envelope[i], across_min[j]);
    if (!std::isfinite(envelope[i])) {
      throw std::invalid_argument(
          "TerrainEnvelope: seabed_z found no surface within " + formatDouble(options.radius_m) +
          " m of the path at arc length " + formatDouble(s[i]) + " m");
    }
  }

  // 3. Hann-weighted mean; the window is renormalised where it is cut by the path's ends.
  const double half_width = options.smoothing_half_width_m;
  const std::size_t smoothing_reach = reach(half_width);
  std::vector<double> smoothed(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t first = i >= smoothing_reach ? i - smoothing_reach : 0;
    const std::size_t last = std::min(count - 1, i + smoothing_reach);
    double weighted = 0.0;
    double total = 0.0;
    for (std::size_t j = first; j <= last; ++j) {
      const double distance = std::abs(s[j] - s[i]);
      const double weight =
          distance < half_width ? 0.5 * (1.0 + std::cos(kPi * distance / half_width)) : 0.0;
      weighted += weight * envelope[j];
      total += weight;
    }
    smoothed[i] = weighted / total;  // total >= 1: the centre sample has weight 1
  }
  return NaturalCubicSpline(std::move(s), std::move(smoothed));
}

}  // namespace hsmap
