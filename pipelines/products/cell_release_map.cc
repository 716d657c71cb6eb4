#include "pipelines/products/cell_release_map.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {
constexpr double kMarginM = 1e-3;

// floor(a / b) for b > 0.
std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
}  // namespace

CellReleaseMap::CellReleaseMap(double cell_m, const std::vector<Eigen::AlignedBox2d>& boxes_xy, double block_m,
                               std::int64_t max_blocks)
    : cell_m_(cell_m), sequences_(std::int64_t(boxes_xy.size())) {
  if (!(cell_m > 0.0) || !std::isfinite(cell_m) || !(block_m > 0.0) || max_blocks < 1) {
    throw std::invalid_argument("CellReleaseMap: cell " + std::to_string(cell_m) + " m, block " +
                                std::to_string(block_m) + " m, " + std::to_string(max_blocks) + " blocks");
  }
  Eigen::AlignedBox2d extent;
  for (const auto& box : boxes_xy) {
    if (!box.isEmpty()) extent.extend(box);
  }
  if (extent.isEmpty()) return;
  extent.min().array() -= kMarginM;
  extent.max().array() += kMarginM;
  const double cells_x = extent.sizes().x() / cell_m + 2.0, cells_y = extent.sizes().y() / cell_m + 2.0;
  m_ = std::max(1, int(std::lround(block_m / cell_m)));
  while ((cells_x / m_ + 2.0) * (cells_y / m_ + 2.0) > double(max_blocks)) m_ *= 2;
  auto blockOf = [&](double x) { return floorDiv(latticeIndex(x, cell_m_), m_); };
  block_x0_ = blockOf(extent.min().x());
  block_y0_ = blockOf(extent.min().y());
  blocks_x_ = blockOf(extent.max().x()) - block_x0_ + 1;
  blocks_y_ = blockOf(extent.max().y()) - block_y0_ + 1;
  last_.assign(std::size_t(blocks_x_ * blocks_y_), -1);
  for (std::int64_t s = 0; s < sequences_; ++s) {
    const Eigen::AlignedBox2d& box = boxes_xy[std::size_t(s)];
    if (box.isEmpty()) continue;
    const std::int64_t x0 = blockOf(box.min().x() - kMarginM) - block_x0_;
    const std::int64_t x1 = blockOf(box.max().x() + kMarginM) - block_x0_;
    const std::int64_t y0 = blockOf(box.min().y() - kMarginM) - block_y0_;
    const std::int64_t y1 = blockOf(box.max().y() + kMarginM) - block_y0_;
    for (std::int64_t x = x0; x <= x1; ++x) {
      for (std::int64_t y = y0; y <= y1; ++y) last_[std::size_t(x * blocks_y_ + y)] = s;  // s increases
    }
  }
}

std::int64_t CellReleaseMap::release(std::int64_t i, std::int64_t j) const {
  const std::int64_t x = floorDiv(i, m_) - block_x0_, y = floorDiv(j, m_) - block_y0_;
  if (x < 0 || y < 0 || x >= blocks_x_ || y >= blocks_y_) return sequences_ - 1;
  const std::int64_t last = last_[std::size_t(x * blocks_y_ + y)];
  return last < 0 ? sequences_ - 1 : last;
}

}  // namespace hsmap
