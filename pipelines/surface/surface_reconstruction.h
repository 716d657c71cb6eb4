#pragma once
// The core of the surface stage in one call: label the Delaunay cells by
// visibility and graph cut (cell_labelling.h), then extract the outward
// surface (surface_extraction.h), with one report of both.

#include "pipelines/surface/cell_labelling.h"
#include "pipelines/surface/surface_mesh.h"

namespace hsmap {

struct SurfaceReconstruction {
  CellLabelling labelling;
  SurfaceMesh mesh;
  SurfaceCutReport report;
};

// Throws as labelCells does.
SurfaceReconstruction reconstructSurface(const VisibilityPoints& points,
                                         const SurfaceCutOptions& options = {});

}  // namespace hsmap
