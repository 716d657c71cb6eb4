#include "core/geometry/local_ned_frame.h"

#include <GeographicLib/Geocentric.hpp>
#include <stdexcept>

namespace hsmap {

namespace {

const GeodeticPoint& validated(const GeodeticPoint& origin) {
  validateGeodeticPoint(origin, "LocalNedFrame origin");
  return origin;
}

}  // namespace

LocalNedFrame::LocalNedFrame(const GeodeticPoint& origin)
    : origin_(validated(origin)),
      enu_(origin.lat_deg, origin.lon_deg, -origin.depth_m, GeographicLib::Geocentric::WGS84()) {}

Eigen::Vector3d LocalNedFrame::toNed(const GeodeticPoint& point) const {
  validateGeodeticPoint(point, "LocalNedFrame::toNed");
  double east = 0.0, north = 0.0, up = 0.0;
  enu_.Forward(point.lat_deg, point.lon_deg, -point.depth_m, east, north, up);
  return {north, east, -up};
}

GeodeticPoint LocalNedFrame::toGeodetic(const Eigen::Vector3d& p_W) const {
  if (!p_W.allFinite()) {
    throw std::invalid_argument("LocalNedFrame::toGeodetic: the NED point must be finite");
  }
  GeodeticPoint point;
  double h = 0.0;
  enu_.Reverse(p_W.y(), p_W.x(), -p_W.z(), point.lat_deg, point.lon_deg, h);
  point.depth_m = -h;
  return point;
}

}  // namespace hsmap
