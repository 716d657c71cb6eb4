#include "pipelines/simulate/swath_footprint.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

namespace hsmap {
namespace {

// A scan line across the track (east from -1 to 1 m) at `north`.
std::vector<Eigen::Vector3d> lineAt(double north, int samples) {
  std::vector<Eigen::Vector3d> points;
  for (int s = 0; s < samples; ++s) {
    points.emplace_back(north, -1.0 + 2.0 * s / (samples - 1), 40.0);
  }
  return points;
}

TEST(SwathFootprint, StraightTrackCoversTheRectangleBetweenFirstAndLastLine) {
  SwathFootprint footprint(-1.0, 3.0, -2.0, 2.0, 0.02, 4);
  for (int j = 0; j <= 100; ++j) footprint.addLine(lineAt(0.02 * j, 201));  // 0..2 m north
  const NorthUpGrid& grid = footprint.grid();
  int inside_missed = 0, outside_marked = 0;
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const double n = grid.northOfRow(row), e = grid.eastOfCol(col);
      const bool inside = n > 0.02 && n < 1.98 && std::abs(e) < 0.98;
      const bool outside = n < -0.02 || n > 2.02 || std::abs(e) > 1.02;
      if (inside && !footprint.covered(row, col)) ++inside_missed;
      if (outside && footprint.covered(row, col)) ++outside_marked;
    }
  }
  EXPECT_EQ(inside_missed, 0);
  EXPECT_EQ(outside_marked, 0);
  // 2 m x 2 m at 2 cm pixels, give or take the border pixels.
  EXPECT_NEAR(double(footprint.coveredCount()), 100.0 * 100.0, 2.0 * 4 * 100);
  int first_row = 0, first_col = 0;
  const NorthUpGrid bounds = footprint.coveredBounds(&first_row, &first_col);
  EXPECT_NEAR(bounds.north_max_m, 2.0, 0.021);
  EXPECT_NEAR(bounds.east_min_m, -1.0, 0.021);
  EXPECT_NEAR(bounds.rows * bounds.pixel_m, 2.0, 0.05);
  EXPECT_NEAR(bounds.cols * bounds.pixel_m, 2.0, 0.05);
}

TEST(SwathFootprint, LinesFarApartStillFillTheBandBetweenThem) {
  // 10 cm between lines, 1 cm pixels: the quads, not the points, cover it.
  SwathFootprint footprint(-1.0, 2.0, -2.0, 2.0, 0.01, 8);
  for (int j = 0; j <= 10; ++j) footprint.addLine(lineAt(0.1 * j, 65));
  const NorthUpGrid& grid = footprint.grid();
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const double n = grid.northOfRow(row), e = grid.eastOfCol(col);
      if (n > 0.01 && n < 0.99 && std::abs(e) < 0.99) {
        ASSERT_TRUE(footprint.covered(row, col)) << n << " " << e;
      }
    }
  }
}

TEST(SwathFootprint, MissingPointsLeaveGapsAndNothingIsInvented) {
  SwathFootprint footprint(-1.0, 2.0, -2.0, 2.0, 0.02, 1);
  auto line = lineAt(0.0, 101);
  auto next = lineAt(0.5, 101);
  for (int s = 40; s <= 60; ++s) next[s].setConstant(std::numeric_limits<double>::quiet_NaN());
  footprint.addLine(line);
  footprint.addLine(next);
  const NorthUpGrid& grid = footprint.grid();
  const int row = int((grid.north_max_m - 0.25) / grid.pixel_m);
  const int centre_col = int((0.0 - grid.east_min_m) / grid.pixel_m);
  const int side_col = int((0.8 - grid.east_min_m) / grid.pixel_m);
  EXPECT_FALSE(footprint.covered(row, centre_col));
  EXPECT_TRUE(footprint.covered(row, side_col));
}

TEST(SwathFootprint, RejectsAnEmptyExtent) {
  EXPECT_THROW(SwathFootprint(1.0, 1.0, 0.0, 1.0, 0.01, 1), std::invalid_argument);
  EXPECT_THROW(SwathFootprint(0.0, 1.0, 0.0, 1.0, 0.0, 1), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
