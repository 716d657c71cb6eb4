#pragma once
// OrthoGrid: the north-up raster of the hyperspectral products, in the UTM
// zone and hemisphere of the survey origin (DATASET.md, "Rasters with a map
// position"): row 0 is the northernmost row, column 0 the westernmost, square
// pixels of `pixel_m`. ENVI's `map info` names the upper-left corner of the
// upper-left pixel:
//   map info = {UTM, 1, 1, west, north, px, px, zone, North|South, WGS-84, units=Meters}
//
// Pixel coordinates follow OpenCV (DATASET.md): the centre of pixel (col, row)
// is at continuous (col, row), so
//   easting  = west  + (col + 0.5) px,    northing = north - (row + 0.5) px
// and the pixel CONTAINING a map point is (floor((e - west) / px),
// floor((north - n) / px)).
//
// coveringUtm() snaps the upper-left corner to whole multiples of the pixel
// size (west = floor(e_min / px) px, north = ceil(n_max / px) px), so rasters
// of one survey at one pixel size share a lattice and line up pixel for pixel
// (a rerun, another variant, the RGB ortho-image on the same grid).
//
// W <-> pixel goes through UtmProjection (W -> geodetic -> UTM and back,
// GeographicLib): pixelOfW() and wOfPixel() below are exact; the hot loops of
// the products stage use WToUtmLattice (w_to_utm_lattice.h) instead.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "core/geometry/utm_projection.h"
#include "core/io/envi_header.h"

namespace hsmap {

struct OrthoGrid {
  double pixel_m = 0.005;
  double west_m = 0.0;   // easting of the left edge of column 0
  double north_m = 0.0;  // northing of the top edge of row 0
  int cols = 0;
  int rows = 0;
  int zone = 0;          // UTM zone 1..60 (the origin's)
  bool northern = true;  // hemisphere

  // The smallest grid of pixel size `pixel_m`, corner snapped to multiples
  // of it, whose pixels contain every point of `bounds_EN` (easting,
  // northing; a point on the east or south edge belongs to the next pixel, so
  // the grid always reaches one pixel past it). std::invalid_argument for an
  // empty box, a non-positive or non-finite pixel size, or a grid of more
  // than 2^31 - 1 rows or columns.
  static OrthoGrid coveringUtm(const Eigen::AlignedBox2d& bounds_EN, double pixel_m, int zone,
                               bool northern);

  std::int64_t pixelCount() const { return std::int64_t(rows) * cols; }

  // Continuous pixel coordinates (col, row) of a map point; pixel centres at integers.
  Eigen::Vector2d pixelOfUtm(const Eigen::Vector2d& en) const {
    return {(en.x() - west_m) / pixel_m - 0.5, (north_m - en.y()) / pixel_m - 0.5};
  }
  // Map position (easting, northing) of continuous pixel coordinates.
  Eigen::Vector2d utmOfPixel(const Eigen::Vector2d& col_row) const {
    return {west_m + (col_row.x() + 0.5) * pixel_m, north_m - (col_row.y() + 0.5) * pixel_m};
  }
  // The pixel containing a map point (may lie outside the grid).
  Eigen::Vector2i containingPixel(const Eigen::Vector2d& en) const;
  bool contains(const Eigen::Vector2i& col_row) const {
    return col_row.x() >= 0 && col_row.y() >= 0 && col_row.x() < cols && col_row.y() < rows;
  }

  // Exact conversions through the survey origin's projection (which must be
  // in this grid's zone: std::invalid_argument otherwise). wOfPixel returns
  // the point of W down-coordinate `down_m` on the vertical through the pixel
  // position (UtmProjection::utmToNed).
  Eigen::Vector2d pixelOfW(const Eigen::Vector3d& p_W, const UtmProjection& projection) const;
  Eigen::Vector3d wOfPixel(const Eigen::Vector2d& col_row, double down_m,
                           const UtmProjection& projection) const;

  // {UTM, 1, 1, west, north, px, px, zone, North|South, WGS-84, units=Meters}
  EnviMapInfo mapInfo() const;
};

}  // namespace hsmap
