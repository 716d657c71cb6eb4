// CellReleaseMap: a column of cells is released after the last scan line
// whose box of hits reaches it, and at the end when none does.
#include "pipelines/products/cell_release_map.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace hsmap {
namespace {

constexpr double kCell = 0.02;

Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1));
}

TEST(CellReleaseMap, ReleasesAColumnAfterTheLastLineWhoseBoxReachesIt) {
  // Line 0 and 2 over x in [0, 1], line 1 over x in [5, 6], line 3 has no hit.
  const std::vector<Eigen::AlignedBox2d> boxes = {box(0, 0, 1, 1), box(5, 0, 6, 1), box(0.5, 0, 1, 1), {}};
  const CellReleaseMap releases(kCell, boxes);
  EXPECT_EQ(releases.release(latticeIndex(0.1, kCell), latticeIndex(0.5, kCell)), 0);
  EXPECT_EQ(releases.release(latticeIndex(0.9, kCell), latticeIndex(0.5, kCell)), 2);
  EXPECT_EQ(releases.release(latticeIndex(5.5, kCell), latticeIndex(0.5, kCell)), 1);
  EXPECT_EQ(releases.release(latticeIndex(50.0, kCell), 0), 3);  // outside every box: at the end
  EXPECT_THROW(CellReleaseMap(0.0, boxes), std::invalid_argument);
}

TEST(CellReleaseMap, BlocksAreWholeCellsAndGrowToStayUnderTheirBound) {
  const std::vector<Eigen::AlignedBox2d> boxes = {box(0, 0, 100, 100)};
  const CellReleaseMap fine(kCell, boxes);
  EXPECT_EQ(fine.cellsPerBlock(), 13);  // round(0.25 m / 2 cm)
  const CellReleaseMap coarse(kCell, boxes, 0.25, 1000);
  EXPECT_GT(coarse.cellsPerBlock(), 13);
  EXPECT_EQ(coarse.release(latticeIndex(50.0, kCell), latticeIndex(50.0, kCell)), 0);
}

}  // namespace
}  // namespace hsmap
