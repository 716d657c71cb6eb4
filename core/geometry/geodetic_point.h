#pragma once
// GeodeticPoint: a position on WGS-84 as the INS reports it (docs/SURVEY_FORMAT.md):
// latitude and longitude in degrees and depth in metres, positive down, i.e.
// the geodetic point (lat, lon, h = -depth).

#include <string>

namespace hsmap {

struct GeodeticPoint {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double depth_m = 0.0;
};

// Throws std::invalid_argument naming `what` unless lat is in [-90, 90], lon in
// [-180, 180] and depth is finite.
void validateGeodeticPoint(const GeodeticPoint& point, const std::string& what);

}  // namespace hsmap
