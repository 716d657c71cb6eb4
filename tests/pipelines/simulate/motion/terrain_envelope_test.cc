#include "pipelines/simulate/motion/terrain_envelope.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace hsmap {
namespace {

// A flat seabed at z = 10 m with a flat-topped boulder (a cylinder of radius
// 0.3 m standing 1 m proud, z = 9) centred at (north, east).
auto seabedWithBoulder(double boulder_north, double boulder_east) {
  return [=](double north, double east) {
    return std::hypot(north - boulder_north, east - boulder_east) <= 0.3 ? 9.0 : 10.0;
  };
}

TEST(TerrainEnvelopeTest, FlatSeabedGivesItsDepth) {
  const LanePath path(20.0, 1, 2.0, 0.0, 0.0);
  const TerrainEnvelope envelope(path, [](double, double) { return 10.0; });
  for (double s = -1.0; s <= 21.0; s += 0.37) {
    EXPECT_NEAR(envelope.z(s), 10.0, 1e-12);
    EXPECT_NEAR(envelope.dzds(s), 0.0, 1e-12);
  }
}

TEST(TerrainEnvelopeTest, RisesFullyOverABoulderOnThePathAndNotFarFromIt) {
  const LanePath path(20.0, 1, 2.0, 0.0, 0.0);
  const TerrainEnvelope envelope(path, seabedWithBoulder(10.0, 0.0));
  // Every envelope sample within 1 m of s = 10 sees the boulder top, and the
  // smoothing window is 1 m: fully raised there.
  EXPECT_NEAR(envelope.z(10.0), 9.0, 1e-12);
  // Beyond boulder radius + envelope radius + smoothing half-width (2.3 m):
  // untouched.
  EXPECT_NEAR(envelope.z(7.6), 10.0, 1e-12);
  EXPECT_NEAR(envelope.z(12.4), 10.0, 1e-12);
  // In between it climbs monotonically (no overshoot below the boulder top).
  double previous = envelope.z(7.6);
  for (double s = 7.6; s <= 10.0; s += 0.05) {
    const double z = envelope.z(s);
    EXPECT_LE(z, previous + 1e-9) << s;
    EXPECT_GE(z, 9.0 - 1e-9) << s;
    previous = z;
  }
}

TEST(TerrainEnvelopeTest, SeesBouldersWithinTheRadiusAcrossTrackOnly) {
  const LanePath path(20.0, 1, 2.0, 0.0, 0.0);
  // Boulder edge 0.7 m east of the path: sampled by the +1 m line.
  EXPECT_NEAR(TerrainEnvelope(path, seabedWithBoulder(10.0, 1.0)).z(10.0), 9.0, 1e-12);
  // 0.5 m west of the path: the -0.5 m line hits it (lines are 0.25 m apart).
  EXPECT_NEAR(TerrainEnvelope(path, seabedWithBoulder(10.0, -0.5)).z(10.0), 9.0, 1e-12);
  // Boulder edge 1.2 m off the path: outside the envelope.
  EXPECT_NEAR(TerrainEnvelope(path, seabedWithBoulder(10.0, 1.5)).z(10.0), 10.0, 1e-12);
}

TEST(TerrainEnvelopeTest, NeverBelowTheSeabedUnderThePath) {
  const LanePath path(6.0, 3, 1.5, 0.0, 0.0);
  const auto seabed = [](double north, double east) {
    return 12.0 + 0.4 * std::sin(1.7 * north) * std::cos(2.3 * east) + 0.2 * std::sin(5.0 * north);
  };
  const TerrainEnvelope envelope(path, seabed);
  // Between two samples 5 cm apart a crest can rise above both by at most
  // |z''| ds^2 / 8 = 8.3 * 0.05^2 / 8 = 2.6e-3 m (|z''| <= 0.4 (1.7^2 + 2.3^2) + 0.2 * 5^2).
  for (double s = 0.0; s <= path.length(); s += 0.013) {
    const PathPoint point = path.at(s);
    EXPECT_LE(envelope.z(s), seabed(point.north_m, point.east_m) + 2.6e-3) << s;
  }
}

TEST(TerrainEnvelopeTest, StaysWithinTheQueryBudgetAndCountsItsCalls) {
  const LanePath path(200.0, 10, 3.0, 0.0, 0.0);  // over 2 km of path
  int calls = 0;
  const TerrainEnvelope envelope(path, [&](double, double) {
    ++calls;
    return 5.0;
  });
  EXPECT_EQ(envelope.queries(), calls);
  EXPECT_LE(calls, 20000);
  EXPECT_GE(calls, 19000);  // the budget is used, not wasted
  // A short path samples every 5 cm: 401 stations x 9 lines.
  int short_calls = 0;
  const TerrainEnvelope short_envelope(LanePath(20.0, 1, 1.0, 0.0, 0.0), [&](double, double) {
    ++short_calls;
    return 5.0;
  });
  EXPECT_EQ(short_calls, 401 * 9);
}

TEST(TerrainEnvelopeTest, SkipsMissingSurfaceButNotEverywhere) {
  const LanePath path(10.0, 1, 1.0, 0.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // No surface west of the path: the rest still defines the envelope.
  const TerrainEnvelope half(path, [&](double, double east) { return east < -0.1 ? nan : 7.0; });
  EXPECT_NEAR(half.z(5.0), 7.0, 1e-12);
  try {
    TerrainEnvelope(path, [&](double north, double) { return north > 4.0 ? nan : 7.0; });
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "TerrainEnvelope: seabed_z found no surface within 1 m of the path at arc length "
                 "5.05 m");
  }
}

TEST(TerrainEnvelopeTest, ValidatesOptions) {
  TerrainEnvelopeOptions options;
  options.smoothing_half_width_m = 1.5;
  try {
    options.validate();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "TerrainEnvelopeOptions: smoothing_half_width_m must be in (0, radius_m], got 1.5");
  }
  options = {};
  options.max_queries = 3;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
