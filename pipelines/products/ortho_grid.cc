#include "pipelines/products/ortho_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

void requireZone(const OrthoGrid& grid, const UtmProjection& projection) {
  if (projection.zone() != grid.zone || projection.northernHemisphere() != grid.northern) {
    throw std::invalid_argument("OrthoGrid: the projection is UTM zone " +
                                std::to_string(projection.zone()) +
                                (projection.northernHemisphere() ? "N" : "S") + ", the grid " +
                                std::to_string(grid.zone) + (grid.northern ? "N" : "S"));
  }
}

}  // namespace

OrthoGrid OrthoGrid::coveringUtm(const Eigen::AlignedBox2d& bounds_EN, double pixel_m, int zone,
                                 bool northern) {
  if (!(pixel_m > 0.0) || !std::isfinite(pixel_m)) {
    throw std::invalid_argument("OrthoGrid: pixel size must be a positive number of metres, got " +
                                std::to_string(pixel_m));
  }
  if (bounds_EN.isEmpty() || !bounds_EN.min().allFinite() || !bounds_EN.max().allFinite()) {
    throw std::invalid_argument("OrthoGrid: empty or non-finite footprint");
  }
  if (zone < 1 || zone > 60) {
    throw std::invalid_argument("OrthoGrid: UTM zone must be 1..60, got " + std::to_string(zone));
  }
  // Whole multiples of the pixel size, kept as integers so that the corner is
  // k * px exactly as the next run computes it.
  const double west_k = std::floor(bounds_EN.min().x() / pixel_m);
  const double east_k = std::floor(bounds_EN.max().x() / pixel_m) + 1.0;
  const double north_k = std::floor(bounds_EN.max().y() / pixel_m) + 1.0;
  const double south_k = std::floor(bounds_EN.min().y() / pixel_m);
  const double cols = east_k - west_k;
  const double rows = north_k - south_k;
  constexpr double kMax = double(std::numeric_limits<int>::max());
  if (cols > kMax || rows > kMax) {
    throw std::invalid_argument("OrthoGrid: " + std::to_string(cols) + " x " + std::to_string(rows) +
                                " pixels is too large; use a larger pixel size");
  }
  OrthoGrid grid;
  grid.pixel_m = pixel_m;
  grid.west_m = west_k * pixel_m;
  grid.north_m = north_k * pixel_m;
  grid.cols = int(cols);
  grid.rows = int(rows);
  grid.zone = zone;
  grid.northern = northern;
  return grid;
}

Eigen::Vector2i OrthoGrid::containingPixel(const Eigen::Vector2d& en) const {
  const double col = std::floor((en.x() - west_m) / pixel_m);
  const double row = std::floor((north_m - en.y()) / pixel_m);
  // Clamp before the cast so that far-away points stay outside, not UB.
  constexpr double kLimit = 1e9;
  return {int(std::clamp(col, -kLimit, kLimit)), int(std::clamp(row, -kLimit, kLimit))};
}

Eigen::Vector2d OrthoGrid::pixelOfW(const Eigen::Vector3d& p_W, const UtmProjection& projection) const {
  requireZone(*this, projection);
  return pixelOfUtm(projection.nedToUtm(p_W));
}

Eigen::Vector3d OrthoGrid::wOfPixel(const Eigen::Vector2d& col_row, double down_m,
                                    const UtmProjection& projection) const {
  requireZone(*this, projection);
  const Eigen::Vector2d en = utmOfPixel(col_row);
  return projection.utmToNed(en.x(), en.y(), down_m);
}

EnviMapInfo OrthoGrid::mapInfo() const {
  EnviMapInfo info;
  info.projection = "UTM";
  info.reference_pixel_x = 1;
  info.reference_pixel_y = 1;
  info.easting = west_m;
  info.northing = north_m;
  info.pixel_size_x = pixel_m;
  info.pixel_size_y = pixel_m;
  info.zone = zone;
  info.north = northern;
  info.datum = "WGS-84";
  info.units = "Meters";
  return info;
}

}  // namespace hsmap
