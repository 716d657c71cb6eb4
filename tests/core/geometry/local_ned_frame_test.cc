#include "core/geometry/local_ned_frame.h"

#include <GeographicLib/Geodesic.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace hsmap {
namespace {

const GeodeticPoint kOrigin{43.0, 5.0, 2.0};

TEST(LocalNedFrame, OriginIsZero) {
  const LocalNedFrame frame(kOrigin);
  EXPECT_LT(frame.toNed(kOrigin).norm(), 1e-9);
}

TEST(LocalNedFrame, NorthMatchesTheGeodesicDistance) {
  // On the ellipsoid (depth 0), where GeographicLib's geodesic distances are measured.
  const GeodeticPoint origin{kOrigin.lat_deg, kOrigin.lon_deg, 0.0};
  const LocalNedFrame frame(origin);
  const GeodeticPoint north{origin.lat_deg + 0.001, origin.lon_deg, 0.0};
  const Eigen::Vector3d p_W = frame.toNed(north);
  double distance = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(origin.lat_deg, origin.lon_deg, north.lat_deg,
                                           north.lon_deg, distance);
  // ~111.09 m at 43 N. The tangent-plane coordinate differs from the arc by
  // s^3 / (6 R^2) ~ 5e-9 m; the point lies s^2 / (2 R) ~ 1 mm below the plane.
  EXPECT_NEAR(p_W.x(), distance, 1e-6);
  EXPECT_GT(p_W.x(), 110.9);
  EXPECT_LT(p_W.x(), 111.2);
  EXPECT_NEAR(p_W.y(), 0.0, 1e-9);
  EXPECT_NEAR(p_W.z(), distance * distance / (2.0 * 6.37e6), 2e-5);
  // East is +y.
  const GeodeticPoint east{origin.lat_deg, origin.lon_deg + 0.001, 0.0};
  EXPECT_GT(frame.toNed(east).y(), 81.0);
  EXPECT_NEAR(frame.toNed(east).x(), 0.0, 1e-3);
}

TEST(LocalNedFrame, DepthMapsToDown) {
  const LocalNedFrame frame(kOrigin);
  const Eigen::Vector3d p_W =
      frame.toNed({kOrigin.lat_deg, kOrigin.lon_deg, kOrigin.depth_m + 25.0});
  EXPECT_NEAR(p_W.x(), 0.0, 1e-9);
  EXPECT_NEAR(p_W.y(), 0.0, 1e-9);
  EXPECT_NEAR(p_W.z(), 25.0, 1e-9);
}

TEST(LocalNedFrame, ToGeodeticInvertsToNed) {
  const LocalNedFrame frame(kOrigin);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> horizontal(-5000.0, 5000.0), vertical(-50.0, 200.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p_W(horizontal(rng), horizontal(rng), vertical(rng));
    const GeodeticPoint point = frame.toGeodetic(p_W);
    EXPECT_LT((frame.toNed(point) - p_W).norm(), 1e-8) << p_W.transpose();
    const GeodeticPoint back = frame.toGeodetic(frame.toNed(point));
    EXPECT_NEAR(back.lat_deg, point.lat_deg, 1e-12);
    EXPECT_NEAR(back.lon_deg, point.lon_deg, 1e-12);
    EXPECT_NEAR(back.depth_m, point.depth_m, 1e-8);
  }
}

TEST(LocalNedFrame, RejectsInvalidCoordinates) {
  const LocalNedFrame frame(kOrigin);
  try {
    frame.toNed({91.0, 5.0, 0.0});
    FAIL() << "latitude 91 was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "LocalNedFrame::toNed: latitude must be in [-90, 90] degrees, got 91");
  }
  EXPECT_THROW(frame.toNed({43.0, 180.5, 0.0}), std::invalid_argument);
  EXPECT_THROW(frame.toNed({43.0, std::nan(""), 0.0}), std::invalid_argument);
  EXPECT_THROW(frame.toNed({43.0, 5.0, INFINITY}), std::invalid_argument);
  EXPECT_THROW(frame.toGeodetic(Eigen::Vector3d(0.0, NAN, 0.0)), std::invalid_argument);
  try {
    LocalNedFrame bad({10.0, -200.0, 0.0});
    FAIL() << "longitude -200 was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "LocalNedFrame origin: longitude must be in [-180, 180] degrees, got -200");
  }
}

}  // namespace
}  // namespace hsmap
