#pragma once
// RasterGrid: the pixel centres of a north-up ENVI raster with a map info
// (DATASET.md, "Rasters with a map position"), and the two readers of it the
// evaluation needs: a truth raster in local W (`Arbitrary`) and a produced
// one in the survey origin's UTM zone.
//
// Pixel centres follow ENVI's reference pixel (1-based corner): row r,
// column c is at
//   x = X + (c + 1.5 - x_ref) px_x,   y = Y - (r + 1.5 - y_ref) px_y,
// x growing east with the column, y north against the row: (east, north) in
// W for a truth raster, (easting, northing) for a produced one.

#include <filesystem>

#include <Eigen/Core>

#include "core/geometry/utm_projection.h"
#include "core/io/envi_header.h"

namespace hsmap {

struct RasterGrid {
  double x0 = 0, y0 = 0;  // centre of pixel (0, 0)
  double px = 1, py = 1;
  int rows = 0, cols = 0;

  Eigen::Vector2d centre(double row, double col) const { return {x0 + col * px, y0 - row * py}; }
  // Continuous (col, row) of a map position.
  Eigen::Vector2d pixel(const Eigen::Vector2d& xy) const {
    return {(xy.x() - x0) / px, (y0 - xy.y()) / py};
  }
};

// The grid of a raster with `map` and rows x cols pixels.
RasterGrid gridOf(const EnviMapInfo& map, int rows, int cols);

// The grid of a truth raster (header `hdr`). InputError naming hdr when the
// map info is missing, not `Arbitrary` or has non-positive pixel sizes.
RasterGrid localRasterGrid(const EnviHeader& header, const std::filesystem::path& hdr);

// The grid of a produced raster. InputError naming hdr when the map info is
// missing, not UTM, in another zone or hemisphere than `utm`'s or has
// non-positive pixel sizes.
RasterGrid utmRasterGrid(const EnviHeader& header, const std::filesystem::path& hdr,
                         const UtmProjection& utm);

}  // namespace hsmap
