#pragma once
// The tiles the dense surface is meshed in (dense_surface.h): squares of
// W's horizontal plane (x north, y east), anchored at W's origin so a point
// belongs to the same tile whatever the survey, each meshed with a margin
// around it and keeping only the triangles whose centroid lies in its
// square. Every triangle of a mesh therefore lands in exactly one tile.

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "core/geometry/pinhole_radtan_camera.h"
#include "pipelines/frontend/visual_map.h"
#include "pipelines/surface/stereo_partner_selection.h"
#include "pipelines/surface/surface_mesh.h"

namespace hsmap {

struct SurfaceTile {
  Eigen::AlignedBox2d core;    // triangles kept: centroid in [min, max)
  Eigen::AlignedBox2d padded;  // points meshed: the core and the margin
  std::vector<int> keyframes;  // references whose depth maps reach the padded square, ascending
};

// The horizontal extent (x, y of W) of everything keyframe can have a depth
// for: its image's border and centre lines cast to the nearest and farthest
// depth searched (partner's range), and its own centre.
Eigen::AlignedBox2d depthFootprint(const Keyframe& keyframe, const StereoPartner& partner,
                                   const PinholeRadtanCamera& camera);

// The tiles of side `size` that some reference's footprint (grown by
// `margin`) reaches, each listing those references, in the order the
// vehicle first reaches them (by their first reference). Keyframes without
// a partner are not references.
std::vector<SurfaceTile> layOutTiles(const VisualMap& map_W,
                                     const std::vector<std::optional<StereoPartner>>& partners,
                                     const PinholeRadtanCamera& camera, double size, double margin);

// Whether p lies in [min, max) on both axes.
bool inHalfOpen(const Eigen::AlignedBox2d& box, const Eigen::Vector2d& p);

// The triangles of `mesh` whose centroid lies in `core` (half-open), on the
// vertices they use, re-indexed in first-use order with point_index kept.
SurfaceMesh cropToTile(const SurfaceMesh& mesh, const Eigen::AlignedBox2d& core);

}  // namespace hsmap
