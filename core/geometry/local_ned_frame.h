#pragma once
// LocalNedFrame: the world frame W of docs/SURVEY_FORMAT.md, the North-East-Down plane
// tangent to WGS-84 at a geodetic origin.
//
// GeographicLib's LocalCartesian does the ellipsoid maths (geodetic ->
// geocentric -> local East-North-Up at the origin); W = (north, east, -up).
// A fix (lat, lon, depth) is the geodetic point (lat, lon, h = -depth), so the
// origin itself maps to (0, 0, 0) and a point 10 m deeper below it to
// (~0, ~0, 10). "Down" here is along the origin's normal: away from the origin
// the tangent plane departs from the ellipsoid (about d^2 / (2 R), 0.8 mm at
// 100 m), which is why down != depth - origin depth exactly.

#include <Eigen/Core>
#include <GeographicLib/LocalCartesian.hpp>

#include "core/geometry/geodetic_point.h"

namespace hsmap {

class LocalNedFrame {
 public:
  // Throws std::invalid_argument for an invalid origin (see validateGeodeticPoint).
  explicit LocalNedFrame(const GeodeticPoint& origin);

  const GeodeticPoint& origin() const { return origin_; }

  // p_W = (north, east, down) in metres. Throws std::invalid_argument for an
  // invalid point.
  Eigen::Vector3d toNed(const GeodeticPoint& point) const;
  // Inverse of toNed. Throws std::invalid_argument for a non-finite p_W.
  GeodeticPoint toGeodetic(const Eigen::Vector3d& p_W) const;

 private:
  GeodeticPoint origin_;
  GeographicLib::LocalCartesian enu_;
};

}  // namespace hsmap
