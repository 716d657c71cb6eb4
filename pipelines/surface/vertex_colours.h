#pragma once
// RGB vertex colours for the surface mesh from the keyframes: each vertex
// (a point of the surface's input) takes its colour from the keyframe,
// among those that saw its point, whose camera is closest to it (the
// sharpest, most detailed view of it; at the near-nadir geometry of a
// survey also the most frontal), sampled bilinearly at the point's
// projection with the full lens model. Each keyframe's image is decoded
// once. A vertex none of whose keyframes sees it inside the image, or whose
// image cannot be decoded, stays mid-grey and is counted.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/survey/rgb_frame_source.h"
#include "pipelines/frontend/visual_map.h"
#include "pipelines/surface/surface_mesh.h"
#include "pipelines/surface/visibility_points.h"

namespace hsmap {

struct VertexColours {
  std::vector<Eigen::Matrix<std::uint8_t, 3, 1>> rgb;  // one per mesh vertex
  int uncoloured = 0;
  int images_decoded = 0;
};

// `points.views` index keyframes of `map_W` (sparse_map_points.h).
VertexColours colourVerticesFromKeyframes(const SurfaceMesh& mesh, const VisibilityPoints& points,
                                          const VisualMap& map_W, const RgbFrameSource& frames,
                                          const PinholeRadtanCamera& camera);

}  // namespace hsmap
