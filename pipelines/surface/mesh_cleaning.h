#pragma once
// Cleaning of the surface stage's mesh before it is textured. The graph cut
// (surface_extraction.h) leaves four kinds of defect on a seabed seen from
// above; cleanMesh removes them in this order:
//
//   1. spikes: a vertex farther from the least-squares plane of its one-ring
//      neighbours than spike_factor x the mean length of its one-ring edges
//      is moved onto that plane (not deleted, so no hole is made). First,
//      because a spike's own edges are long and step 2 would cut them out.
//   2. long-edge triangles: the Delaunay joins far points at the convex
//      hull's rim and across holes; a triangle with an edge longer than
//      max_edge_factor x the median edge length (or max_edge_m) goes.
//   3. non-manifold places: an edge of 4 facets (two matter cells touching
//      along an edge) or a pinched vertex is split by giving the vertex one
//      copy per fan of triangles around it (the cut-and-stitch of Gueziec
//      et al. 2001, as CGAL's orient_polygon_soup does, here on flat
//      arrays in linear time: CGAL's took 1.7 s of 4 on 530 000
//      triangles); both copies keep the input's point_index. Two triangles
//      on one edge in the same direction (one is wrongly oriented; the cut
//      does not make these) are both dropped. No triangle is ever flipped:
//      every kept triangle keeps its input orientation (outward, towards
//      the cameras).
//   4. small connected components (CGAL connected_components): floating
//      bits from outlier points, with fewer triangles than
//      min_component_fraction x the largest component's.
//
// and then smooths lightly by implicit mean-curvature flow (CGAL's
// smooth_shape: Desbrun et al. 1999 with the cotangent Laplacian, stiffness
// fixed after Kazhdan et al. 2012), which moves vertices along the surface
// normal, not across the surface as tangential relaxation or
// angle-and-area smoothing do, with the border vertices held fixed; a
// vertex whose move would turn a triangle over (slivers of the cut) is put
// back. Its
// shrinkage of relief grows with curvature, its damping of noise with
// frequency, so a short step removes noise at the edge length and barely
// touches relief at the scale of the seabed's shapes.
//
// The result is a new SurfaceMesh on the surviving vertices, re-indexed
// densely in the order of the input's vertices (a vertex split at a
// non-manifold place comes out once per copy), with point_index carried
// over. On a 530 000-triangle noisy seabed sheet (20 m x 3 m at 1.5 cm)
// cleaning takes 1.6-2.0 s on one core, three quarters of it smoothing.

#include <string>

#include "pipelines/surface/surface_mesh.h"

namespace hsmap {

struct MeshCleaningOptions {
  // A triangle with an edge longer than this x the median edge length of
  // the mesh is removed. The graph cut's triangles on a seabed have edges
  // near the point spacing, up to ~3x it on 70 deg slopes seen from above
  // (the points' spacing is set in the image); edges of 5x and more join
  // points that are not neighbours on the surface (hull rim, holes).
  // 0 turns the relative test off.
  double max_edge_factor = 5.0;
  // Absolute cap on edge length in metres, applied as well as the relative
  // one; 0 = none.
  double max_edge_m = 0.0;
  // A connected component (through edges) with fewer triangles than this
  // fraction of the largest component's is removed: floating bits from
  // outlier points are tens of triangles, the seabed sheet hundreds of
  // thousands. Relative, so that a hole that splits the sheet in two big
  // parts keeps both. 0 keeps every component; 1 keeps only the largest
  // (and any of the same size).
  double min_component_fraction = 0.01;
  // A vertex whose distance to the plane fitted (least squares) to its
  // one-ring neighbours exceeds this x the mean length of its one-ring edges
  // is a spike and is moved onto that plane. The ratio is the sine of the
  // slope of the vertex's edges above its neighbours' plane: a vertex pulled
  // out by d >> h (edge length h) scores ~1 (a 10 cm spike on 1.5 cm edges:
  // 0.99; 2 cm: 0.8), noise of 1 mm on 1.5 cm edges ~0.1, a vertex on a
  // 90 deg ridge roughly 0.3. 0.75 flags single-vertex cones steeper than ~50 deg all round.
  // 0 turns it off.
  double spike_factor = 0.75;
  // Steps of implicit mean-curvature flow (CGAL smooth_shape); 0 turns
  // smoothing off.
  int smoothing_iterations = 1;
  // Time of one step, in units of the squared median edge length h^2.
  // 0.1 h^2 halves 1 mm of vertex noise on 1.5 cm edges (RMS to the true
  // surface 0.99 -> 0.47 mm) while the peak of a 10 cm high Gaussian bump
  // of sigma 30 cm comes down by 0.2 mm
  // (tests/pipelines/surface/mesh_cleaning_test.cc).
  double smoothing_step = 0.1;

  // Empty when the options are usable, otherwise what is wrong.
  std::string validate() const;
};

struct MeshCleaningReport {
  long long input_triangles = 0;
  long long invalid_triangles = 0;       // an index out of range or repeated
  long long spikes = 0;                  // step 1: vertices moved onto their neighbours' plane
  long long long_edge_triangles = 0;     // step 2
  long long inconsistent_triangles = 0;  // step 3: dropped, orientation clash with a neighbour
  long long non_manifold_edges = 0;      // step 3: edges of > 2 triangles, split
  long long duplicated_vertices = 0;     // step 3: vertex copies made to split non-manifold places
  long long components_removed = 0;      // step 4
  long long component_triangles = 0;     // step 4: triangles in them
  long long smoothing_rejected =
      0;  // smoothed vertices put back: moved > half an edge or turned a triangle over
  long long vertices_removed = 0;  // input vertices in no output triangle
  long long output_triangles = 0;
  double median_edge_m = 0.0;  // of the input's triangles
  double seconds = 0.0;
};

// Throws std::invalid_argument when options.validate() is not empty.
SurfaceMesh cleanMesh(const SurfaceMesh& mesh, const MeshCleaningOptions& options,
                      MeshCleaningReport* report = nullptr);

}  // namespace hsmap
