#include "pipelines/evaluate/true_surface_samples.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "core/io/envi_reader.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

std::int64_t ceilDiv(std::int64_t a, std::int64_t b) { return (a + b - 1) / b; }

std::int64_t latticePixels(int rows, int cols, std::int64_t stride) {
  return ceilDiv(rows, stride) * ceilDiv(cols, stride);
}

// The map info of a truth raster: local W (DATASET.md, "Rasters with a map
// position"). A UTM raster read as local W would be off by the origin's
// easting and northing, so anything else is refused.
const EnviMapInfo& localMapInfo(const EnviHeader& header, const std::filesystem::path& hdr_path) {
  if (!header.map_info) {
    throw InputError(hdr_path, InputError::atKey("map info"),
                     "missing: expected map info = {Arbitrary, 1, 1, E, N, px, px, "
                     "units=Meters} giving the raster's position in W");
  }
  const EnviMapInfo& map = *header.map_info;
  if (map.projection != "Arbitrary") {
    throw InputError(hdr_path, InputError::atKey("map info"),
                     "projection " + map.projection +
                         ": expected Arbitrary (east and north in the survey's local W)");
  }
  if (!(map.pixel_size_x > 0.0) || !(map.pixel_size_y > 0.0)) {
    throw InputError(hdr_path, InputError::atKey("map info"),
                     "expected positive pixel sizes");
  }
  return map;
}

}  // namespace

int footprintStride(int rows, int cols, std::int64_t max_samples) {
  if (rows <= 0 || cols <= 0 || max_samples <= 0) {
    throw std::invalid_argument("footprintStride: expected positive rows, cols and max_samples");
  }
  // Start from the continuous estimate sqrt(rows cols / max) and step up to
  // absorb the rounding up of the lattice's sides.
  const double pixels = static_cast<double>(rows) * static_cast<double>(cols);
  std::int64_t stride =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(std::sqrt(pixels / max_samples)));
  while (latticePixels(rows, cols, stride) > max_samples) ++stride;
  return static_cast<int>(stride);
}

TrueSurfaceSamples sampleTrueSurface(const MeshRayCaster& scene,
                                     const std::filesystem::path& reflectance_hdr,
                                     std::int64_t max_samples) {
  const EnviReader reader(reflectance_hdr);
  const EnviMapInfo& map = localMapInfo(reader.header(), reflectance_hdr);
  const int rows = reader.lines();
  const int cols = reader.samples();
  const int bands = reader.bands();

  TrueSurfaceSamples samples;
  samples.stride = footprintStride(rows, cols, max_samples);
  const int stride = samples.stride;

  // North and east of every valid pixel centre on the lattice.
  std::vector<Eigen::Vector2d> north_east;
  Eigen::MatrixXf line;  // bands x cols
  for (int r = 0; r < rows; r += stride) {
    reader.readLine(r, line);
    const double north = map.northing - (r + 1.5 - map.reference_pixel_y) * map.pixel_size_y;
    for (int c = 0; c < cols; c += stride) {
      bool valid = false;
      for (int b = 0; b < bands && !valid; ++b) valid = !std::isnan(line(b, c));
      if (!valid) continue;
      const double east = map.easting + (c + 1.5 - map.reference_pixel_x) * map.pixel_size_x;
      north_east.emplace_back(north, east);
    }
  }
  samples.footprint_pixels = static_cast<std::int64_t>(north_east.size());

  // Vertical rays from 1 m above the scene's highest point (smallest down),
  // downwards: the first hit is the topmost surface.
  const double start_down = scene.bounds().min().z() - 1.0;
  std::vector<RayHit> hits(north_east.size());
  constexpr std::size_t kBatch = 256;  // neighbouring pixels: coherent rays for Embree
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, north_east.size(), kBatch),
      [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<Ray> rays(range.size());
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          Ray& ray = rays[i - range.begin()];
          ray.origin = Eigen::Vector3d(north_east[i].x(), north_east[i].y(), start_down);
          ray.direction = Eigen::Vector3d::UnitZ();
        }
        scene.intersect(rays, std::span<RayHit>(hits.data() + range.begin(), range.size()));
      });

  samples.points_W.reserve(north_east.size());
  for (std::size_t i = 0; i < north_east.size(); ++i) {
    if (!hits[i].hit()) {
      ++samples.missed_pixels;
      continue;
    }
    samples.points_W.emplace_back(north_east[i].x(), north_east[i].y(),
                                  start_down + hits[i].distance);
  }
  return samples;
}

}  // namespace hsmap
