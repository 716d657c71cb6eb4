#pragma once
// buildSeabedScene: the simulator's seabed as one triangle soup in W, the
// geometry that the RGB and hyperspectral renderers ray-cast.
//
// Contents:
//   - the bare seabed: SeabedHeightField sampled on a regular north/east grid
//     covering [north_min_m, north_max_m] x [east_min_m, east_max_m] exactly
//     (spacing cell_m, shrunk slightly where the extent is not a multiple of
//     it), two triangles per cell, kind seabed, normals up (-z);
//   - rugged preset only: rocks, kind rock, each a closed mesh with outward
//     normals (rock_mesh.h), partly sunk into the seabed:
//       * boulders 0.2-0.8 m across (small ones more frequent), one at a
//         random place in each 1.5 m (north) x 2 m (east) cell of the extent,
//         the cells aligned so that one column is the vehicle's corridor
//         |east| <= 1 m: a boulder every 1.5 m along the track, and the same
//         density under the other lanes of a lawnmower survey;
//       * a perched boulder (0.8 m across resting on a smaller pedestal rock,
//         its underside 0.2-0.4 m above the seabed) at 20% of the north
//         extent, and a tilted slab (1.3 m x 0.8 m, one end on the seabed,
//         the other on a support rock) at 82%: overhangs that a height field
//         cannot hold. Both lie inside the corridor.
//     No rock rises more than 1 m above the seabed around it.
//   flat and low-relief scenes have no rocks.
//   Everything above is in the build frame (seabed_scene_config.h); a
//   heading_deg turns the finished scene about the pivot into W, and a slope
//   tilts the height field, so rocks placed on it move with it.
//
// Winding: triangle (a, b, c) has the outward normal (b - a) x (c - a).
// Vertices and triangles are listed grid first (row by row, north index
// major), then rock by rock. Deterministic: the same config gives
// bit-identical vectors (the grid is filled in parallel, but each vertex is a
// pure function of its indices).
//
// Size and time: the default rugged scene (26 m x 6 m at 2 cm, seed 1) has
// 0.47M vertices and 0.94M triangles (0.78M of them the grid), about 24 MB,
// and builds in 0.1-0.3 s on 2 cores (benchmarks/simulate_scene_bench.cc).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "pipelines/simulate/scene/seabed_scene_config.h"

namespace hsmap {

enum class SurfaceKind : std::uint8_t { seabed = 0, rock = 1 };

struct SeabedScene {
  std::vector<Eigen::Vector3d> vertices;   // in W
  std::vector<Eigen::Vector3i> triangles;  // outward normals (seabed: pointing up, i.e. -z)
  std::vector<SurfaceKind> triangle_kind;  // one per triangle
};

// Throws std::invalid_argument when config.validate() does.
SeabedScene buildSeabedScene(const SeabedSceneConfig& config);

}  // namespace hsmap
