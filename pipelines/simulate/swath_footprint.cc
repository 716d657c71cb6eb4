#include "pipelines/simulate/swath_footprint.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hsmap {
namespace {
bool finite(const Eigen::Vector3d& p) { return p.allFinite(); }
// (north, east) -> (column, row) in continuous pixel units (pixel centres at +0.5).
Eigen::Vector2d toPixel(const NorthUpGrid& grid, const Eigen::Vector3d& p_W) {
  return Eigen::Vector2d((p_W.y() - grid.east_min_m) / grid.pixel_m,
                         (grid.north_max_m - p_W.x()) / grid.pixel_m);
}
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}
}  // namespace

SwathFootprint::SwathFootprint(double north_min_m, double north_max_m, double east_min_m,
                               double east_max_m, double pixel_m, int stride)
    : stride_(std::max(1, stride)) {
  if (!(pixel_m > 0.0) || !(north_max_m > north_min_m) || !(east_max_m > east_min_m)) {
    throw std::invalid_argument("SwathFootprint: expected a non-empty extent and pixel_m > 0");
  }
  grid_.pixel_m = pixel_m;
  grid_.north_max_m = std::ceil(north_max_m / pixel_m) * pixel_m;
  grid_.east_min_m = std::floor(east_min_m / pixel_m) * pixel_m;
  grid_.rows = static_cast<int>(std::ceil((grid_.north_max_m - north_min_m) / pixel_m));
  grid_.cols = static_cast<int>(std::ceil((east_max_m - grid_.east_min_m) / pixel_m));
  mask_.assign(std::size_t(grid_.rows) * grid_.cols, 0);
}

void SwathFootprint::markPoint(const Eigen::Vector3d& p_W) {
  const Eigen::Vector2d pixel = toPixel(grid_, p_W);
  const int col = static_cast<int>(std::floor(pixel.x()));
  const int row = static_cast<int>(std::floor(pixel.y()));
  if (row >= 0 && row < grid_.rows && col >= 0 && col < grid_.cols) {
    mask_[std::size_t(row) * grid_.cols + col] = 1;
  }
}

void SwathFootprint::fillTriangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                  const Eigen::Vector2d& c) {
  const double area = cross(a, b, c);
  if (area == 0.0) return;
  const int col_begin = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) - 0.5)));
  const int col_end = std::min(grid_.cols - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
  const int row_begin = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) - 0.5)));
  const int row_end = std::min(grid_.rows - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
  for (int row = row_begin; row <= row_end; ++row) {
    for (int col = col_begin; col <= col_end; ++col) {
      const Eigen::Vector2d centre(col + 0.5, row + 0.5);
      const double w0 = cross(b, c, centre) / area;
      const double w1 = cross(c, a, centre) / area;
      const double w2 = cross(a, b, centre) / area;
      if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) mask_[std::size_t(row) * grid_.cols + col] = 1;
    }
  }
}

void SwathFootprint::addLine(const std::vector<Eigen::Vector3d>& points_W) {
  for (const Eigen::Vector3d& p : points_W) {
    if (finite(p)) markPoint(p);
  }
  if (previous_.size() == points_W.size()) {
    const int samples = static_cast<int>(points_W.size());
    int s = 0;
    while (s < samples - 1) {
      const int next = std::min(samples - 1, s + stride_);
      const Eigen::Vector3d& a = previous_[s];
      const Eigen::Vector3d& b = previous_[next];
      const Eigen::Vector3d& c = points_W[next];
      const Eigen::Vector3d& d = points_W[s];
      if (finite(a) && finite(b) && finite(c) && finite(d)) {
        const Eigen::Vector2d pa = toPixel(grid_, a), pb = toPixel(grid_, b);
        const Eigen::Vector2d pc = toPixel(grid_, c), pd = toPixel(grid_, d);
        fillTriangle(pa, pb, pc);
        fillTriangle(pa, pc, pd);
      }
      s = next;
    }
  }
  previous_ = points_W;
}

std::int64_t SwathFootprint::coveredCount() const {
  return std::count(mask_.begin(), mask_.end(), std::uint8_t(1));
}

NorthUpGrid SwathFootprint::coveredBounds(int* first_row, int* first_col) const {
  int row_min = grid_.rows, row_max = -1, col_min = grid_.cols, col_max = -1;
  for (int row = 0; row < grid_.rows; ++row) {
    for (int col = 0; col < grid_.cols; ++col) {
      if (!covered(row, col)) continue;
      row_min = std::min(row_min, row);
      row_max = std::max(row_max, row);
      col_min = std::min(col_min, col);
      col_max = std::max(col_max, col);
    }
  }
  NorthUpGrid bounds = grid_;
  if (row_max < 0) {
    bounds.rows = bounds.cols = 0;
    *first_row = *first_col = 0;
    return bounds;
  }
  bounds.north_max_m = grid_.north_max_m - row_min * grid_.pixel_m;
  bounds.east_min_m = grid_.east_min_m + col_min * grid_.pixel_m;
  bounds.rows = row_max - row_min + 1;
  bounds.cols = col_max - col_min + 1;
  *first_row = row_min;
  *first_col = col_min;
  return bounds;
}

}  // namespace hsmap
