#pragma once
// Visibility-based inside/outside labelling of the 3D Delaunay
// tetrahedralisation of the points (Labatut et al. 2009; Jancosek & Pajdla
// 2014; OpenMVS's ReconstructMesh): every cell, the unbounded ones
// included, is a node of an s-t graph whose capacities come from the
// visibility rays (visibility_evidence.h); the minimum cut (min_cut.h)
// labels each cell free space (outside) or matter (inside). The surface is
// the set of facets between the two (surface_extraction.h). Nothing here
// assumes a height field: overhangs seen by cameras are kept.

#include <cstdint>
#include <memory>

#include <Eigen/Core>

#include "pipelines/surface/surface_cut_options.h"
#include "pipelines/surface/visibility_points.h"

namespace hsmap {

namespace surface_detail {
struct LabelledDelaunay;
}

struct SurfaceCutReport {
  std::int64_t points = 0;          // input points
  std::int64_t vertices = 0;        // distinct points in the triangulation
  std::int64_t cells = 0;           // graph nodes: all cells, unbounded ones included
  std::int64_t finite_cells = 0;
  std::int64_t inside_cells = 0;    // cells labelled matter (unbounded ones included)
  std::int64_t rays = 0;            // visibility rays traced
  std::int64_t rays_cut_short = 0;  // walks stopped by max_cells_per_ray
  std::int64_t cells_crossed = 0;   // over all walks
  std::int64_t skipped_steps = 0;   // walk steps through an edge or vertex (no facet weighted)
  std::int64_t grazing_rays = 0;    // rays leaving the hull at their point (no matter evidence)
  std::int64_t facets_in_cut = 0;   // triangles of the surface (set by reconstructSurface)
  double flow = 0.0;                // the cut's cost
  double seconds_triangulation = 0.0;
  double seconds_rays = 0.0;
  double seconds_cut = 0.0;
  double seconds_extraction = 0.0;  // set by reconstructSurface
  double seconds_total = 0.0;
};

// The labelled triangulation. Cheap to copy (shared, immutable).
class CellLabelling {
 public:
  explicit CellLabelling(std::shared_ptr<const surface_detail::LabelledDelaunay> cells);
  // Whether x lies in a cell labelled matter (on a facet, edge or vertex:
  // in one of the cells that hold it, the one CGAL's locate returns).
  bool isInside(const Eigen::Vector3d& x) const;
  const surface_detail::LabelledDelaunay& cells() const { return *cells_; }

 private:
  std::shared_ptr<const surface_detail::LabelledDelaunay> cells_;
};

// Triangulates points.p_W, traces every (point, camera) ray and cuts.
// Throws std::invalid_argument when points or options do not validate, and
// std::runtime_error when the points span less than a volume (all on one
// plane or line: no tetrahedra to label). `report` may be null.
CellLabelling labelCells(const VisibilityPoints& points, const SurfaceCutOptions& options,
                         SurfaceCutReport* report = nullptr);

}  // namespace hsmap
