#pragma once
// The surface mesh (RUN/map/mesh.ply, in W) seen from straight above: each
// pixel shows the topmost triangle over it (the smallest `down`), in its
// vertex colours shaded by a light from the north-west, so that relief
// reads at a glance. A z-buffer rasteriser: no window, no GPU, a few
// hundred milliseconds for a million triangles. The height grid it keeps
// gives the seabed under the trajectory for the depth/altitude profile.

#include <opencv2/core.hpp>

#include "core/io/ply_io.h"

namespace hsmap {

struct MeshTopView {
  cv::Mat image;  // BGR; the page's background where no triangle lies
  cv::Mat down;   // CV_32F, `down` of the topmost surface per pixel, NaN where none
  double north_max = 0.0, east_min = 0.0;  // W of the upper-left corner of the upper-left pixel
  double pixel_m = 0.0;

  // The surface's `down` under (north, east): NaN outside or where no triangle lies.
  double downAt(double north, double east) const;
};

// The view's longer side is `max_side` pixels. std::invalid_argument for a
// mesh without triangles.
MeshTopView rasteriseMeshTopView(const PlyMesh& mesh, int max_side);

}  // namespace hsmap
