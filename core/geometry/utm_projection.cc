#include "core/geometry/utm_projection.h"

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/UTMUPS.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

namespace {

// utmToNed searches the height whose W down-coordinate is the one asked for;
// d(down)/dh is -cos(angle between the two normals), ~ -1 within a survey, so
// the fixed-point iteration gains many digits per step.
constexpr int kMaxHeightIterations = 20;
constexpr double kDownTolerance_m = 1e-9;

const GeodeticPoint& validated(const GeodeticPoint& origin) {
  validateGeodeticPoint(origin, "UtmProjection origin");
  return origin;
}

}  // namespace

UtmProjection::UtmProjection(const GeodeticPoint& origin) : frame_(validated(origin)) {
  zone_ = GeographicLib::UTMUPS::StandardZone(origin.lat_deg, origin.lon_deg);
  if (zone_ == GeographicLib::UTMUPS::UPS) {
    std::ostringstream problem;
    problem << "UtmProjection: origin latitude " << origin.lat_deg
            << " is in a polar region, where UTM is not defined (expected [-80, 84])";
    throw std::invalid_argument(problem.str());
  }
  northern_ = origin.lat_deg >= 0.0;
  double easting = 0.0, northing = 0.0, scale = 0.0;
  int zone = 0;
  bool northern = true;
  GeographicLib::UTMUPS::Forward(origin.lat_deg, origin.lon_deg, zone, northern, easting, northing,
                                 convergence_deg_, scale, zone_);
}

Eigen::Vector2d UtmProjection::geodeticToUtm(const GeodeticPoint& point) const {
  validateGeodeticPoint(point, "UtmProjection::geodeticToUtm");
  try {
    int zone = 0;
    bool northern = true;
    double easting = 0.0, northing = 0.0;
    GeographicLib::UTMUPS::Forward(point.lat_deg, point.lon_deg, zone, northern, easting, northing,
                                   zone_);
    // A point across the equator from the origin: express it in the origin's
    // hemisphere (false northing changes by 10,000 km).
    if (northern != northern_) {
      int zone_out = 0;
      GeographicLib::UTMUPS::Transfer(zone, northern, easting, northing, zone_, northern_, easting,
                                      northing, zone_out);
    }
    return {easting, northing};
  } catch (const GeographicLib::GeographicErr& error) {
    std::ostringstream problem;
    problem.precision(12);
    problem << "UtmProjection: cannot project lat " << point.lat_deg << ", lon " << point.lon_deg
            << " in UTM zone " << zone_ << (northern_ ? "N" : "S") << ": " << error.what();
    throw std::invalid_argument(problem.str());
  }
}

Eigen::Vector2d UtmProjection::nedToUtm(const Eigen::Vector3d& p_W) const {
  return geodeticToUtm(frame_.toGeodetic(p_W));
}

Eigen::Vector3d UtmProjection::utmToNed(double easting, double northing, double down) const {
  if (!(std::isfinite(easting) && std::isfinite(northing) && std::isfinite(down))) {
    throw std::invalid_argument("UtmProjection::utmToNed: easting, northing and down must be finite");
  }
  GeodeticPoint point;
  try {
    GeographicLib::UTMUPS::Reverse(zone_, northern_, easting, northing, point.lat_deg,
                                   point.lon_deg);
  } catch (const GeographicLib::GeographicErr& error) {
    std::ostringstream problem;
    problem.precision(12);
    problem << "UtmProjection: easting " << easting << ", northing " << northing
            << " is outside UTM zone " << zone_ << (northern_ ? "N" : "S") << ": "
            << error.what();
    throw std::invalid_argument(problem.str());
  }
  // Start from the depth that gives `down` on the origin's vertical.
  point.depth_m = frame_.origin().depth_m + down;
  Eigen::Vector3d p_W = frame_.toNed(point);
  for (int i = 0; i < kMaxHeightIterations && std::abs(p_W.z() - down) > kDownTolerance_m; ++i) {
    point.depth_m -= p_W.z() - down;
    p_W = frame_.toNed(point);
  }
  return p_W;
}

}  // namespace hsmap
