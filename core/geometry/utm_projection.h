#pragma once
// UtmProjection: UTM coordinates in the zone and hemisphere of a survey's
// origin, for map products (docs/SURVEY_FORMAT.md "Rasters with a map position").
//
// GeographicLib's UTMUPS does the projection. Every point is projected in the
// ORIGIN's zone and hemisphere (GeographicLib extends a zone a few degrees
// beyond its edges), so one survey gives one consistent grid even when it
// straddles a zone edge or the equator.
//
// (easting, northing) of a point in W is the UTM projection of its latitude
// and longitude (its height plays no part). Conversely utmToNed(e, n, down)
// takes the vertical line (along the ellipsoid normal) through the geodetic
// point of (e, n) and returns the point on it whose W down-coordinate is
// `down`, so nedToUtm and utmToNed are exact inverses.
//
// Meridian convergence gamma (degrees) is GeographicLib's: the bearing of grid
// north measured clockwise from true north. At the origin, a displacement of
// d metres towards true north moves the map position by
// (easting, northing) += d * (-sin gamma, cos gamma) (times the point scale).

#include <Eigen/Core>

#include "core/geometry/geodetic_point.h"
#include "core/geometry/local_ned_frame.h"

namespace hsmap {

class UtmProjection {
 public:
  // Throws std::invalid_argument for an invalid origin or one in the polar
  // regions (latitude beyond [-80, 84]) where UTM is not defined.
  explicit UtmProjection(const GeodeticPoint& origin);

  int zone() const { return zone_; }  // 1..60
  bool northernHemisphere() const { return northern_; }
  const LocalNedFrame& frame() const { return frame_; }

  // (easting, northing) in metres. Throws std::invalid_argument when the point
  // is too far from the zone for GeographicLib to project it.
  Eigen::Vector2d geodeticToUtm(const GeodeticPoint& point) const;
  Eigen::Vector2d nedToUtm(const Eigen::Vector3d& p_W) const;
  Eigen::Vector3d utmToNed(double easting, double northing, double down) const;

  double meridianConvergenceDeg() const { return convergence_deg_; }

 private:
  LocalNedFrame frame_;
  int zone_ = 0;
  bool northern_ = true;
  double convergence_deg_ = 0.0;
};

}  // namespace hsmap
