#include "core/geometry/geodetic_point.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {

void validateGeodeticPoint(const GeodeticPoint& point, const std::string& what) {
  std::ostringstream problem;
  problem.precision(17);
  if (!(std::isfinite(point.lat_deg) && point.lat_deg >= -90.0 && point.lat_deg <= 90.0)) {
    problem << what << ": latitude must be in [-90, 90] degrees, got " << point.lat_deg;
  } else if (!(std::isfinite(point.lon_deg) && point.lon_deg >= -180.0 &&
               point.lon_deg <= 180.0)) {
    problem << what << ": longitude must be in [-180, 180] degrees, got " << point.lon_deg;
  } else if (!std::isfinite(point.depth_m)) {
    problem << what << ": depth must be finite, got " << point.depth_m;
  } else {
    return;
  }
  throw std::invalid_argument(problem.str());
}

}  // namespace hsmap
