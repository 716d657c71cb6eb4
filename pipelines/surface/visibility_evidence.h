#pragma once
// Turns visibility rays into the cut graph's capacities (Labatut et al.
// 2009, section 3.2). For the ray from camera c to point p, with weight w:
//   - the cells the segment p -> c crosses are walked with CGAL's segment
//     traverser, from the cell at p towards the camera, until the camera's
//     cell or the first unbounded cell (the ray has left the hull: all
//     beyond is free); each facet crossed from cell A (camera side) into
//     cell B gets w on A -> B: labelling A outside and B inside would put a
//     surface in front of a point that was seen;
//   - the first cell beyond p along c -> p gets w to the sink (matter
//     behind a seen surface point), unless that cell is unbounded (the ray
//     leaves the hull at p: see the .cc for why that gives no evidence);
//   - the camera's cell (and the unbounded cell where the ray left the hull)
//     is tied to the source (free space).
// The walk starts at the point's vertex rather than at the camera so that
// it always starts inside the hull, where CGAL's traverser is defined for
// any segment.

#include <cstdint>

#include "pipelines/surface/delaunay_cells.h"
#include "pipelines/surface/min_cut.h"
#include "pipelines/surface/surface_cut_options.h"
#include "pipelines/surface/visibility_points.h"

namespace hsmap::surface_detail {

// The capacities of the cut graph over the cells of a triangulation, node
// = cell->info(): terminal capacities per cell and, per cell and facet i,
// the capacity from the cell into cell->neighbor(i).
struct CellEvidence {
  std::vector<double> source;  // per cell: cost of labelling it inside
  std::vector<double> sink;    // per cell: cost of labelling it outside
  std::vector<double> across;  // per cell, 4 each: cost of (cell outside, neighbour(i) inside)

  explicit CellEvidence(int cells) : source(cells, 0.0), sink(cells, 0.0), across(4 * cells, 0.0) {}
};

struct RayCounts {
  std::int64_t rays = 0;            // rays traced
  std::int64_t cut_short = 0;       // walks stopped by max_cells_per_ray
  std::int64_t cells_crossed = 0;   // cells visited over all walks
  std::int64_t skipped_steps = 0;   // steps between cells sharing no facet (ray through an edge)
  std::int64_t grazing = 0;         // rays leaving the hull at their point (no matter evidence)
};

// The cell incident to v that the ray from v towards t enters (exact
// predicates; on a facet or edge, one of the cells holding it).
Delaunay::Cell_handle cellAlongRay(const Delaunay& tr, Delaunay::Vertex_handle v, const Point& t);

// Adds the evidence of every ray of `points`. `vertex_of_point[i]` is point
// i's vertex in `tr`.
RayCounts addVisibilityEvidence(const Delaunay& tr, const VisibilityPoints& points,
                                const std::vector<Delaunay::Vertex_handle>& vertex_of_point,
                                const SurfaceCutOptions& options, CellEvidence& evidence);

// The prior and area terms (surface_cut_options.h). An unbounded cell faces
// a camera when a camera that saw one of its hull facet's points lies
// strictly on the outer side of that facet.
void addPriorAndAreaTerms(const Delaunay& tr, const VisibilityPoints& points,
                          const SurfaceCutOptions& options, CellEvidence& evidence);

// One link per facet of `tr` (the bounded and the unbounded ones).
CutGraph toCutGraph(const Delaunay& tr, const CellEvidence& evidence);

}  // namespace hsmap::surface_detail
