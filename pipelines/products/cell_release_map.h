#pragma once
// CellReleaseMap: after which scan line no more hits can land in a cell of
// the hyperspectral point cloud's lattice, so that a cell is written as soon
// as the survey has passed it, and never before (spectral_cell_binner.h).
//
// The lattice: cubes of side c in W, cell (i, j, k) = floor(p_W / c)
// (latticeIndex). Cells are grouped in columns of m x m cells in (x, y), all
// k together (a "block"), m = max(1, round(block_m / c)), so that every cell
// lies in exactly one block.
//
// Built from the (x, y) box of every scan line's hits in processing order
// (sequence 0, 1, ...; an empty box for a line without hits), each grown by
// 1 mm (the boxes come from a cast of their own; the margin keeps a hit on a
// box's edge inside it). A block's release is the LAST sequence whose box
// touches it. A hit of sequence s lies in the box of s, so its block's
// release is >= s: once the release sequence has been processed, no later
// hit can reach any cell of the block. Boxes over-cover a line's footprint
// (a line running diagonally covers the square of its swath), which only
// delays a release.
//
// Memory: 8 bytes a block over the boxes' (x, y) extent; the block grows
// (in whole cells) until there are at most `max_blocks` blocks.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <vector>

namespace hsmap {

// The lattice index of a coordinate for cells of `cell_m` metres.
inline std::int64_t latticeIndex(double coordinate_m, double cell_m) {
  return std::int64_t(std::floor(coordinate_m / cell_m));
}

class CellReleaseMap {
 public:
  // `boxes_xy[s]`: the (x, y) box of sequence s's hits in W (empty: none).
  // std::invalid_argument for a cell or block size that is not > 0.
  CellReleaseMap(double cell_m, const std::vector<Eigen::AlignedBox2d>& boxes_xy, double block_m = 0.25,
                 std::int64_t max_blocks = std::int64_t(1) << 24);

  double cellSize() const { return cell_m_; }
  int cellsPerBlock() const { return m_; }
  std::int64_t sequences() const { return sequences_; }
  // The last sequence that can add a hit to the cells of column (i, j);
  // sequences() - 1 (the end) outside every box.
  std::int64_t release(std::int64_t i, std::int64_t j) const;

 private:
  double cell_m_;
  int m_ = 1;
  std::int64_t sequences_ = 0;
  std::int64_t block_x0_ = 0, block_y0_ = 0, blocks_x_ = 0, blocks_y_ = 0;
  std::vector<std::int64_t> last_;  // per block, row-major in (x, y); -1 untouched
};

}  // namespace hsmap
