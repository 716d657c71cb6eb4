#pragma once
// The surface stage: RUN/georef/ (the adjusted map, or the planar poses) ->
// RUN/surface/mesh.ply (surface_meshing.h; docs/SURFACE.md).

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runSurfaceStage(const StageContext& context, const SurfaceStageOptions& options);

}  // namespace hsmap
