#pragma once
// The products stage: every scan line cast onto the surface and written
// (docs/PRODUCTS.md). It only casts and writes; nothing in it estimates.
//
//   reads   RUN/trajectory/uhi_lines.csv and RUN/map/mesh.ply (the run's
//           current answer, as published by the stages before it)
//   writes  RUN/hyperspectral/ (ortho-image ENVI + GeoTIFF, quick-look,
//           ancillary layers, points.ply), RUN/map/rgb_ortho.png (+ .tif)
//   stacked: the scan lines side by side into RUN/hyperspectral/, no map
//           position (no GeoTIFF, no RGB ortho-image)

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runProductsStage(const StageContext& context, const ProductsStageOptions& options);

}  // namespace hsmap
