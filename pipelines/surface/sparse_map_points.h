#pragma once
// The surface stage's input from the geo-referenced sparse map (the
// reference paper's way, `sparse`): every landmark seen by at least two
// keyframes is a point, and each keyframe that observed it a camera centre
// whose ray to it crossed free space. The map's frame must be W (the
// georef stage's adjusted map: keyframe poses T_W_C, landmarks p_W).

#include "pipelines/frontend/visual_map.h"
#include "pipelines/surface/visibility_points.h"

namespace hsmap {

// Cameras are indexed by keyframe id.
VisibilityPoints visibilityFromSparseMap(const VisualMap& map_W);

}  // namespace hsmap
