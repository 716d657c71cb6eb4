#include "pipelines/simulate/scene/seabed_scene_config.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

std::string text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

[[noreturn]] void fail(const std::string& detail) {
  throw std::invalid_argument("SeabedSceneConfig: " + detail);
}

void requireFinite(const char* name, double value) {
  if (!std::isfinite(value)) fail(std::string(name) + " must be finite, got " + text(value));
}

}  // namespace

void SeabedSceneConfig::validate() const {
  requireFinite("north_min_m", north_min_m);
  requireFinite("north_max_m", north_max_m);
  requireFinite("east_min_m", east_min_m);
  requireFinite("east_max_m", east_max_m);
  requireFinite("seabed_depth_m", seabed_depth_m);
  requireFinite("cell_m", cell_m);
  requireFinite("heading_deg", heading_deg);
  requireFinite("pivot_north_m", pivot_north_m);
  requireFinite("pivot_east_m", pivot_east_m);
  requireFinite("slope_direction_deg", slope_direction_deg);
  if (!(slope_deg >= 0.0 && slope_deg < 80.0)) {
    fail("slope_deg must be in [0, 80), got " + text(slope_deg));
  }
  if (!(north_max_m > north_min_m)) {
    fail("north_max_m must be greater than north_min_m, got " + text(north_min_m) + " .. " +
         text(north_max_m));
  }
  if (!(east_max_m > east_min_m)) {
    fail("east_max_m must be greater than east_min_m, got " + text(east_min_m) + " .. " +
         text(east_max_m));
  }
  if (!(cell_m > 0.0)) fail("cell_m must be positive, got " + text(cell_m));
  const double north_m = north_max_m - north_min_m, east_m = east_max_m - east_min_m;
  if (cell_m > north_m || cell_m > east_m) {
    fail("cell_m must not exceed the extent (" + text(north_m) + " m x " + text(east_m) +
         " m), got " + text(cell_m));
  }
  const double vertices = (std::ceil(north_m / cell_m) + 1.0) * (std::ceil(east_m / cell_m) + 1.0);
  if (vertices > kMaxGridVertices) {
    fail("cell_m " + text(cell_m) + " gives " + text(vertices) + " grid vertices, at most " +
         text(kMaxGridVertices) + " are allowed");
  }
}

}  // namespace hsmap
