#pragma once
// SwathFootprint: the part of the seabed, seen from above, that the UHI's scan
// lines looked at. truth/reflectance is valid (not NaN) exactly there.
//
// A north-up grid over a fixed extent of W (row 0 northernmost, column 0
// westernmost, square pixels of `pixel_m`). Consecutive scan lines' surface
// points (the pixels' central rays) span quadrilaterals; every grid pixel
// whose centre lies in one of them, or that holds one of the points, is
// marked. Samples are taken every `stride` pixels along the line (chosen so
// that neighbours are closer than half a grid pixel); the first and last
// samples are always used, so the swath's edges are exact.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace hsmap {

struct NorthUpGrid {
  double north_max_m = 0.0;  // north of the top edge of row 0
  double east_min_m = 0.0;   // east of the left edge of column 0
  double pixel_m = 0.01;
  int rows = 0;
  int cols = 0;
  double northOfRow(int row) const { return north_max_m - (row + 0.5) * pixel_m; }
  double eastOfCol(int col) const { return east_min_m + (col + 0.5) * pixel_m; }
};

class SwathFootprint {
 public:
  // Covers [north_min, north_max] x [east_min, east_max] (rounded outwards to pixels).
  SwathFootprint(double north_min_m, double north_max_m, double east_min_m, double east_max_m,
                 double pixel_m, int stride);

  // Adds scan line `points_W` (NaN entries: no surface) and the band between it
  // and the previous line added.
  void addLine(const std::vector<Eigen::Vector3d>& points_W);

  const NorthUpGrid& grid() const { return grid_; }
  bool covered(int row, int col) const { return mask_[std::size_t(row) * grid_.cols + col] != 0; }
  std::int64_t coveredCount() const;
  // The smallest sub-grid holding every covered pixel (rows = 0 when none).
  NorthUpGrid coveredBounds(int* first_row, int* first_col) const;

 private:
  void markPoint(const Eigen::Vector3d& p_W);
  void fillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

  NorthUpGrid grid_;
  int stride_;
  std::vector<std::uint8_t> mask_;
  std::vector<Eigen::Vector3d> previous_;
};

}  // namespace hsmap
