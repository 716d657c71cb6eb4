#include "core/geometry/utm_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace hsmap {
namespace {

const GeodeticPoint kOrigin{43.0, 5.0, 3.0};

TEST(UtmProjection, ZoneAndHemisphereAreTheOrigins) {
  const UtmProjection marseille(kOrigin);
  EXPECT_EQ(marseille.zone(), 31);
  EXPECT_TRUE(marseille.northernHemisphere());
  const UtmProjection cape_town({-33.9, 18.4, 0.0});
  EXPECT_EQ(cape_town.zone(), 34);
  EXPECT_FALSE(cape_town.northernHemisphere());
}

TEST(UtmProjection, CentralMeridianHasTheFalseEasting) {
  // Zone 31's central meridian is 3 E; its easting is 500 km exactly.
  const UtmProjection utm(kOrigin);
  EXPECT_NEAR(utm.geodeticToUtm({43.0, 3.0, 0.0}).x(), 500000.0, 1e-6);
  EXPECT_NEAR(utm.geodeticToUtm({0.0, 3.0, 0.0}).y(), 0.0, 1e-6);
}

TEST(UtmProjection, NedToUtmToNedRoundTrips) {
  const UtmProjection utm(kOrigin);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> horizontal(-3000.0, 3000.0), vertical(-20.0, 150.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p_W(horizontal(rng), horizontal(rng), vertical(rng));
    const Eigen::Vector2d en = utm.nedToUtm(p_W);
    EXPECT_LT((utm.utmToNed(en.x(), en.y(), p_W.z()) - p_W).norm(), 1e-7) << p_W.transpose();
  }
  // The origin's map position is the one of its latitude and longitude.
  const Eigen::Vector2d origin_en = utm.nedToUtm(Eigen::Vector3d::Zero());
  EXPECT_LT((origin_en - utm.geodeticToUtm(kOrigin)).norm(), 1e-8);
}

TEST(UtmProjection, ConvergenceIsTheAngleFromTrueToGridNorth) {
  // East of the central meridian in the northern hemisphere, grid north points
  // east of true north: gamma ~ (lon - lon0) sin(lat) > 0.
  const UtmProjection utm(kOrigin);
  const double gamma = utm.meridianConvergenceDeg();
  EXPECT_GT(gamma, 0.0);
  EXPECT_NEAR(gamma, 2.0 * std::sin(43.0 * M_PI / 180.0), 0.01);
  // Walking true north moves the map position at bearing -gamma on the grid.
  const Eigen::Vector2d start = utm.nedToUtm(Eigen::Vector3d::Zero());
  const Eigen::Vector2d moved = utm.nedToUtm(Eigen::Vector3d(100.0, 0.0, 0.0));
  const Eigen::Vector2d step = moved - start;
  EXPECT_NEAR(std::atan2(-step.x(), step.y()) * 180.0 / M_PI, gamma, 1e-4);

  EXPECT_LT(UtmProjection({43.0, 1.0, 0.0}).meridianConvergenceDeg(), 0.0);  // west of 3 E
  EXPECT_LT(UtmProjection({-43.0, 5.0, 0.0}).meridianConvergenceDeg(), 0.0);  // southern
}

TEST(UtmProjection, PointsAcrossTheEquatorStayInTheOriginsHemisphere) {
  const UtmProjection utm({0.005, 5.0, 0.0});
  const Eigen::Vector3d south_of_equator(-1500.0, 200.0, 10.0);
  const Eigen::Vector2d en = utm.nedToUtm(south_of_equator);
  EXPECT_LT(en.y(), 0.0);  // northern-hemisphere northing, continuous across the equator
  EXPECT_LT((utm.utmToNed(en.x(), en.y(), 10.0) - south_of_equator).norm(), 1e-7);
}

TEST(UtmProjection, RejectsPolarOriginsAndInvalidInput) {
  try {
    UtmProjection polar({85.0, 5.0, 0.0});
    FAIL() << "a polar origin was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "UtmProjection: origin latitude 85 is in a polar region, where UTM is not defined "
              "(expected [-80, 84])");
  }
  EXPECT_THROW(UtmProjection({-95.0, 5.0, 0.0}), std::invalid_argument);
  const UtmProjection utm(kOrigin);
  EXPECT_THROW(utm.utmToNed(NAN, 4.7e6, 0.0), std::invalid_argument);
  EXPECT_THROW(utm.geodeticToUtm({43.0, 100.0, 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
