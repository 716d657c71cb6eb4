#include "pipelines/evaluate/ortho_raster_grid.h"

#include <string>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

const EnviMapInfo& requireMapInfo(const EnviHeader& header, const std::filesystem::path& hdr,
                                  const char* expected) {
  if (!header.map_info) {
    throw InputError(hdr, InputError::atKey("map info"),
                     std::string("missing: expected map info = ") + expected);
  }
  const EnviMapInfo& map = *header.map_info;
  if (!(map.pixel_size_x > 0.0) || !(map.pixel_size_y > 0.0)) {
    throw InputError(hdr, InputError::atKey("map info"), "expected positive pixel sizes");
  }
  return map;
}

}  // namespace

RasterGrid gridOf(const EnviMapInfo& map, int rows, int cols) {
  RasterGrid grid;
  grid.px = map.pixel_size_x;
  grid.py = map.pixel_size_y;
  grid.x0 = map.easting + (1.5 - map.reference_pixel_x) * map.pixel_size_x;
  grid.y0 = map.northing - (1.5 - map.reference_pixel_y) * map.pixel_size_y;
  grid.rows = rows;
  grid.cols = cols;
  return grid;
}

RasterGrid localRasterGrid(const EnviHeader& header, const std::filesystem::path& hdr) {
  const EnviMapInfo& map =
      requireMapInfo(header, hdr, "{Arbitrary, 1, 1, E, N, px, px, units=Meters} in W");
  if (map.projection != "Arbitrary") {
    throw InputError(hdr, InputError::atKey("map info"),
                     "projection " + map.projection +
                         ": expected Arbitrary (east and north in the survey's local W)");
  }
  return gridOf(map, header.lines, header.samples);
}

RasterGrid utmRasterGrid(const EnviHeader& header, const std::filesystem::path& hdr,
                         const UtmProjection& utm) {
  const EnviMapInfo& map = requireMapInfo(
      header, hdr, "{UTM, 1, 1, easting, northing, px, px, zone, North|South, WGS-84, units=Meters}");
  const std::string hemisphere = utm.northernHemisphere() ? "North" : "South";
  if (map.projection != "UTM") {
    throw InputError(hdr, InputError::atKey("map info"),
                     "projection " + map.projection + ": expected UTM (zone " +
                         std::to_string(utm.zone()) + " " + hemisphere + ", the survey origin's)");
  }
  if (map.zone != utm.zone() || map.north != utm.northernHemisphere()) {
    throw InputError(hdr, InputError::atKey("map info"),
                     "UTM zone " + std::to_string(map.zone) + (map.north ? " North" : " South") +
                         ": expected zone " + std::to_string(utm.zone()) + " " + hemisphere +
                         ", the survey origin's");
  }
  return gridOf(map, header.lines, header.samples);
}

}  // namespace hsmap
