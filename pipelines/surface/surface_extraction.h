#pragma once
// The surface of a labelled tetrahedralisation: every facet between a cell
// labelled matter and one labelled free space, as a triangle oriented
// towards the free-space cell (outward), on the triangulation's vertices
// re-indexed densely (only the vertices some triangle uses, in the order
// of their input point index).

#include "pipelines/surface/cell_labelling.h"
#include "pipelines/surface/surface_mesh.h"

namespace hsmap {

SurfaceMesh extractSurface(const CellLabelling& labelling);

}  // namespace hsmap
