#pragma once
// The dense surface of a survey (`hsmap run --surface dense`, docs/SURFACE.md):
// a depth map for every keyframe from its stereo partner
// (stereo_partner_selection.h, stereo_pair_points.h), the depth maps fused
// into one point per voxel with the keyframes that saw it
// (voxel_point_fusion.h), and the points meshed by the visibility graph cut
// (surface_reconstruction.h), cleaned (mesh_cleaning.h) and coloured from
// the keyframes (vertex_colours.h).
//
// Bounded memory: the survey is meshed in square tiles of the horizontal
// plane of W, each with a margin around it. A tile fuses and meshes the
// points of its square and margin, from the depth maps of the keyframes
// whose footprint (the landmarks they observe) reaches it, and keeps the
// triangles whose centroid falls in its square. Tiles go in the order the
// vehicle first reaches them; a depth map is computed once and freed when the
// last tile needing it is done, and a point keeps its voxel key from one tile
// to the next, so neighbouring tiles share the vertices on their seam. Peak
// memory follows the depth maps and points of a tile and its neighbours,
// not the survey's length; only the finished mesh grows with it.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/survey/rgb_frame_source.h"
#include "pipelines/frontend/visual_map.h"
#include "pipelines/surface/mesh_cleaning.h"
#include "pipelines/surface/stereo_pair_points.h"
#include "pipelines/surface/stereo_partner_selection.h"
#include "pipelines/surface/surface_cut_options.h"

namespace hsmap {

struct DenseSurfaceOptions {
  StereoPartnerOptions partners;
  StereoPairOptions stereo;        // its depth range is set per keyframe from the landmarks
  double voxel_size_m = 0.02;      // one fused point per voxel
  int min_support = 2;             // depth maps that must agree on a voxel
  // Visibility rays per fused point, spread over the keyframes that saw it:
  // the rays' cost dominates the graph cut, and a few directions already
  // carve the free space in front of a seabed point.
  int max_views_per_point = 4;
  // A keyframe gets a depth map when it is at least this x its depth from
  // the previous one that did (0: every keyframe with a partner). At 0.05
  // and 2 m, one depth map every 10 cm or more: on `rugged` (keyframes 11 cm
  // apart on average) 152 of 184, the surface stage 25 % faster for 0.4 %
  // of completeness; 0.1 halves the depth maps but loses 4 % of it (fewer
  // depth maps agree at the swath's edges and on the boulders' sides).
  double reference_spacing_ratio = 0.05;
  double tile_size_m = 6.0;        // side of a tile's square
  double tile_margin_m = 0.5;      // meshed around it so its edges are not its hull's
  SurfaceCutOptions cut;
  MeshCleaningOptions cleaning;

  DenseSurfaceOptions();
  std::string validate() const;
};

struct DenseSurfaceReport {
  int keyframes = 0;
  int keyframes_with_partner = 0;
  int references = 0;               // keyframes given a depth map (reference_spacing_ratio)
  int depth_maps = 0;               // computed
  int depth_maps_failed = 0;        // pairs whose rectification or matching failed
  std::int64_t depth_points = 0;    // over all depth maps
  std::int64_t fused_points = 0;    // over all tiles (points of margins counted in each)
  std::int64_t rays = 0;
  int tiles = 0;
  int max_depth_maps_held = 0;      // the most depth maps in memory at once
  std::int64_t cleaned_triangles = 0;  // removed by the cleaning
  int uncoloured_vertices = 0;
  double seconds_depth = 0.0;
  double seconds_fusion = 0.0;
  double seconds_cut = 0.0;
  double seconds_cleaning = 0.0;
  double seconds_colour = 0.0;
  std::vector<std::string> warnings;

  // A paragraph for people.
  std::string summary() const;
};

struct DenseSurface {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> colours;  // RGB, one per vertex
  DenseSurfaceReport report;
};

// Progress callback: (what, done, total) with what "depth maps" or "tiles".
using DenseSurfaceProgress = std::function<void(const std::string&, int, int)>;

// `map_W`: the adjusted sparse map in W (keyframe poses T_W_C as T_F_C,
// landmarks). Throws std::invalid_argument for invalid options and
// std::runtime_error when no keyframe has a stereo partner.
DenseSurface reconstructDenseSurface(const VisualMap& map_W, const RgbFrameSource& frames,
                                     const PinholeRadtanCamera& camera,
                                     const DenseSurfaceOptions& options,
                                     const DenseSurfaceProgress& progress = {});

}  // namespace hsmap
