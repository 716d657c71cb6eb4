#pragma once
// SeabedSceneConfig: what seabed to build (terrain preset, extent, grid
// spacing, seed). Used by seabed_height_field.h and seabed_scene.h.
//
// Frames and units: W is local North-East-Down in metres (z DOWN), so the
// seabed lies at z_W around +seabed_depth_m and "up" is -z. The extent is a
// north/east rectangle of the scene's build frame, in which the vehicle flies
// north along east = 0 over it. The build frame is W turned by heading_deg
// about the pivot: buildSeabedScene turns the finished scene (rocks and all)
// by heading_deg clockwise about (pivot_north_m, pivot_east_m), so that it
// lies under a track heading that way. At heading_deg = 0 it is W itself.
//
// A slope adds a plane to the seabed in W: the depth grows by tan(slope_deg)
// per metre towards slope_direction_deg (clockwise from north), and the plane
// is zero at the pivot (the track's start).

#include <cstdint>

#include "pipelines/simulate/scene/terrain_preset.h"

namespace hsmap {

struct SeabedSceneConfig {
  TerrainPreset terrain = TerrainPreset::rugged;
  double north_min_m = -3.0, north_max_m = 23.0;  // extent of the seabed in W
  double east_min_m = -3.0, east_max_m = 3.0;
  double seabed_depth_m = 40.0;  // mean z_W of the seabed (positive: below the origin)
  double cell_m = 0.02;          // grid spacing of the seabed height field
  std::uint64_t seed = 1;
  double heading_deg = 0.0;       // the build frame's north axis in W, clockwise from north
  double pivot_north_m = 0.0;     // the point of W the scene turns about (its position is
  double pivot_east_m = 0.0;      //   the same in both frames)
  double slope_deg = 0.0;            // in [0, 80)
  double slope_direction_deg = 0.0;  // downhill, in W, clockwise from north

  // Largest height-field grid accepted (vertices): 26 m x 6 m at 2 mm, about
  // 2 GB of mesh; a finer request is almost certainly a unit mistake.
  static constexpr double kMaxGridVertices = 4e7;

  // Throws std::invalid_argument naming the field and what was expected:
  // finite values, north_max_m > north_min_m, east_max_m > east_min_m,
  // cell_m > 0 and not larger than either side of the extent, and at most
  // kMaxGridVertices grid vertices, finite heading, pivot and slope
  // direction, slope_deg in [0, 80).
  void validate() const;
};

}  // namespace hsmap
