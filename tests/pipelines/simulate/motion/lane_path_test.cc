#include "pipelines/simulate/motion/lane_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(LanePathTest, TransectIsAStraightLineNorth) {
  const LanePath path(20.0, 1, 2.0, 5.0, -3.0);
  EXPECT_EQ(path.length(), 20.0);
  EXPECT_EQ(path.turnLength(), 0.0);
  for (double s : {0.0, 7.5, 20.0}) {
    const PathPoint point = path.at(s);
    EXPECT_EQ(point.north_m, 5.0 + s);
    EXPECT_EQ(point.east_m, -3.0);
    EXPECT_EQ(point.heading_rad, 0.0);
  }
  // Clamped outside [0, length].
  EXPECT_EQ(path.at(-1.0).north_m, 5.0);
  EXPECT_EQ(path.at(25.0).north_m, 25.0);
}

// A first-lane heading turns the whole path, U-turns included, about its
// start: every point is the north-heading path's point rotated there.
TEST(LanePathTest, HeadingTurnsTheWholePathAboutItsStart) {
  const double heading_deg = 35.0;
  const LanePath north(10.0, 3, 2.0, 1.0, 4.0);
  const LanePath turned(10.0, 3, 2.0, 1.0, 4.0, heading_deg);
  EXPECT_EQ(turned.length(), north.length());
  const double h = heading_deg * kPi / 180.0;
  for (double s = 0.0; s <= north.length(); s += 0.37) {
    const PathPoint a = north.at(s);
    const PathPoint b = turned.at(s);
    const double dn = a.north_m - 1.0, de = a.east_m - 4.0;
    EXPECT_NEAR(b.north_m, 1.0 + std::cos(h) * dn - std::sin(h) * de, 1e-12) << "s " << s;
    EXPECT_NEAR(b.east_m, 4.0 + std::sin(h) * dn + std::cos(h) * de, 1e-12) << "s " << s;
    EXPECT_NEAR(b.heading_rad, a.heading_rad + h, 1e-12) << "s " << s;
  }
  // The first lane runs along the heading; the second starts to its right.
  const PathPoint end_of_first = turned.at(10.0);
  EXPECT_NEAR(std::atan2(end_of_first.east_m - 4.0, end_of_first.north_m - 1.0), h, 1e-12);
  const PathPoint second = turned.at(10.0 + turned.turnLength());
  const double right_n = -std::sin(h), right_e = std::cos(h);
  EXPECT_NEAR((second.north_m - end_of_first.north_m) * right_n +
                  (second.east_m - end_of_first.east_m) * right_e,
              2.0, 1e-9);
  EXPECT_THROW(LanePath(10.0, 1, 2.0, 0.0, 0.0, NAN), std::invalid_argument);
}

TEST(LanePathTest, LawnmowerLanesAlternateAndTurnsLandOnTheNextLane) {
  const double length = 10.0, spacing = 2.0;
  const LanePath path(length, 3, spacing, 1.0, 4.0);
  const double turn = path.turnLength();
  EXPECT_GT(turn, kPi * spacing / 2.0);  // longer than the semicircle it replaces
  EXPECT_DOUBLE_EQ(path.length(), 3 * length + 2 * turn);

  // Lane 1 runs south at east 6; lane 2 north at east 8.
  const PathPoint lane1 = path.at(length + turn + 2.5);
  EXPECT_NEAR(lane1.north_m, 1.0 + length - 2.5, 1e-12);
  EXPECT_NEAR(lane1.east_m, 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(lane1.heading_rad, kPi);
  const PathPoint lane2 = path.at(2 * (length + turn) + 2.5);
  EXPECT_NEAR(lane2.north_m, 3.5, 1e-12);
  EXPECT_NEAR(lane2.east_m, 8.0, 1e-12);
  EXPECT_DOUBLE_EQ(lane2.heading_rad, 0.0);

  // The first turn ends level with the lane end (C(1) = 0) and on lane 1,
  // just before the lane code takes over.
  const PathPoint turn_end = path.at(length + turn * (1.0 - 1e-12));
  EXPECT_NEAR(turn_end.north_m, 1.0 + length, 1e-9);
  EXPECT_NEAR(turn_end.east_m, 6.0, 1e-9);
  EXPECT_NEAR(turn_end.heading_rad, kPi, 1e-9);
  // Halfway through a turn: heading east, half the spacing across (symmetry).
  const PathPoint mid_first = path.at(length + turn / 2);
  EXPECT_NEAR(mid_first.heading_rad, kPi / 2, 1e-13);  // s rounds at ~4e-15 m
  EXPECT_NEAR(mid_first.east_m, 5.0, 1e-12);
  EXPECT_GT(mid_first.north_m, 1.0 + length);
  const PathPoint mid_second = path.at(2 * length + 1.5 * turn);
  EXPECT_NEAR(mid_second.heading_rad, kPi / 2, 1e-13);
  EXPECT_NEAR(mid_second.east_m, 7.0, 1e-12);
  EXPECT_LT(mid_second.north_m, 1.0);
}

TEST(LanePathTest, PositionAdvancesAlongTheHeadingAtUnitRate) {
  // d(north, east)/ds = (cos, sin)(heading): s is arc length and the
  // quadrature of the turns agrees with their heading.
  const LanePath path(6.0, 4, 1.5, 0.0, 0.0);
  const double h = 1e-5;
  for (double s = h; s < path.length() - h; s += 0.0731) {
    const PathPoint before = path.at(s - h), at = path.at(s), after = path.at(s + h);
    EXPECT_NEAR((after.north_m - before.north_m) / (2 * h), std::cos(at.heading_rad), 1e-7) << s;
    EXPECT_NEAR((after.east_m - before.east_m) / (2 * h), std::sin(at.heading_rad), 1e-7) << s;
  }
}

TEST(LanePathTest, CurvatureStartsAtZeroSoHeadingIsC2AtLaneEnds) {
  // heading = pi g(u), g(u) = 10 u^3 + O(u^4): the curvature is 0 at the
  // junction and grows like u^2, with no step.
  const LanePath path(10.0, 2, 2.0, 0.0, 0.0);
  const double turn = path.turnLength();
  for (double u : {1e-3, 1e-2}) {
    const double heading = path.at(10.0 + u * turn).heading_rad;
    const double g = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
    EXPECT_NEAR(heading, kPi * g, 1e-15);
  }
  EXPECT_EQ(path.at(10.0).heading_rad, 0.0);
}

TEST(LanePathTest, RejectsBadGeometry) {
  try {
    LanePath(10.0, 0, 2.0, 0.0, 0.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "LanePath: expected at least 1 lane, got 0");
  }
  EXPECT_THROW(LanePath(0.0, 1, 2.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(LanePath(10.0, 2, 0.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(LanePath(10.0, 1, 2.0, NAN, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
