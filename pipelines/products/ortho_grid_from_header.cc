#include "pipelines/products/ortho_grid_from_header.h"

#include <cmath>
#include <stdexcept>

namespace hsmap {

OrthoGrid orthoGridFromHeader(const EnviHeader& header) {
  if (!header.map_info || header.map_info->projection != "UTM") {
    throw std::invalid_argument("orthoGridFromHeader: the header has no UTM map info");
  }
  const EnviMapInfo& info = *header.map_info;
  if (!(info.pixel_size_x > 0.0) || std::abs(info.pixel_size_x - info.pixel_size_y) > 1e-12) {
    throw std::invalid_argument("orthoGridFromHeader: pixels must be square");
  }
  OrthoGrid grid;
  grid.pixel_m = info.pixel_size_x;
  grid.west_m = info.easting - (info.reference_pixel_x - 1.0) * grid.pixel_m;
  grid.north_m = info.northing + (info.reference_pixel_y - 1.0) * grid.pixel_m;
  grid.cols = header.samples;
  grid.rows = header.lines;
  grid.zone = info.zone;
  grid.northern = info.north;
  return grid;
}

}  // namespace hsmap
