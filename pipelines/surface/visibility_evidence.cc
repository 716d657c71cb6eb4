#include "pipelines/surface/visibility_evidence.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <cmath>

#include <Eigen/Geometry>

namespace hsmap::surface_detail {
namespace {

// Capacity tying a camera's cell to the source: the camera is surely in free
// space, so no finite sum of evidence should move it.
constexpr double kPinned = 1e30;

Point toPoint(const Eigen::Vector3d& x) { return Point(x.x(), x.y(), x.z()); }
Eigen::Vector3d toEigen(const Point& x) { return {x.x(), x.y(), x.z()}; }

// Labatut et al. 2009's soft visibility: the weight of a crossed facet at
// distance d in front of the point.
double softWeight(double w, double d, double sigma) {
  if (sigma <= 0.0) return w;
  return w * (1.0 - std::exp(-d * d / (2.0 * sigma * sigma)));
}

}  // namespace

Delaunay::Cell_handle cellAlongRay(const Delaunay& tr, Delaunay::Vertex_handle v, const Point& t) {
  std::vector<Delaunay::Cell_handle> cells;
  tr.incident_cells(v, std::back_inserter(cells));
  Delaunay::Cell_handle unbounded;
  for (const Delaunay::Cell_handle& cell : cells) {
    std::array<const Point*, 4> corner;
    int infinite = -1;
    for (int j = 0; j < 4; ++j) {
      if (tr.is_infinite(cell->vertex(j))) {
        infinite = j;
        corner[j] = &t;
      } else {
        corner[j] = &cell->vertex(j)->point();
      }
    }
    if (infinite >= 0) {
      // The ray leaves the hull at v through this cell's hull facet when t
      // is beyond that facet (CGAL's convention: an unbounded cell with
      // the infinite vertex replaced by a point beyond is positive).
      if (unbounded == Delaunay::Cell_handle() &&
          CGAL::orientation(*corner[0], *corner[1], *corner[2], *corner[3]) == CGAL::POSITIVE)
        unbounded = cell;
      continue;
    }
    // A bounded cell is positively oriented; t is in the cone of the cell at
    // v when replacing any other vertex j by t keeps it so (t on vertex j's
    // side of the facet through v opposite j). On a facet counts as in.
    const int i = cell->index(v);
    bool in_cone = true;
    for (int j = 0; j < 4 && in_cone; ++j) {
      if (j == i) continue;
      std::array<const Point*, 4> q = corner;
      q[j] = &t;
      in_cone = CGAL::orientation(*q[0], *q[1], *q[2], *q[3]) != CGAL::NEGATIVE;
    }
    if (in_cone) return cell;
  }
  return unbounded != Delaunay::Cell_handle() ? unbounded : v->cell();
}

RayCounts addVisibilityEvidence(const Delaunay& tr, const VisibilityPoints& points,
                                const std::vector<Delaunay::Vertex_handle>& vertex_of_point,
                                const SurfaceCutOptions& options, CellEvidence& evidence) {
  RayCounts counts;
  std::vector<Delaunay::Cell_handle> camera_cell(points.c_W.size());
  Delaunay::Cell_handle hint;
  for (std::size_t k = 0; k < points.c_W.size(); ++k) {
    camera_cell[k] = tr.locate(toPoint(points.c_W[k]), hint);
    hint = camera_cell[k];
  }
  for (std::size_t i = 0; i < points.p_W.size(); ++i) {
    const Delaunay::Vertex_handle v = vertex_of_point[i];
    const Eigen::Vector3d& p = points.p_W[i];
    const double w = options.visibility_weight * points.weight(i);
    for (int k : points.views[i]) {
      const Eigen::Vector3d& c = points.c_W[k];
      ++counts.rays;
      evidence.source[camera_cell[k]->info()] += kPinned;
      // Matter just beyond the point: the cell at p that the ray enters when
      // continued past it. When that cell is unbounded the ray leaves the
      // hull at p; that is as often a ray grazing a sharp edge (a point on
      // a box's face next to its edge, seen at a slant: the continuation
      // leaves through the neighbouring face within a hair) as the back of
      // the matter, so no ray puts matter outside the hull; unbounded cells
      // get matter from the prior alone (surface_cut_options.h).
      const Delaunay::Cell_handle behind = cellAlongRay(tr, v, toPoint(p + (p - c)));
      if (tr.is_infinite(behind))
        ++counts.grazing;
      else
        evidence.sink[behind->info()] += w;
      // Free space from the point back to the camera. CGAL's traverser
      // starts from a vertex in any cell incident to it, so the first cell
      // is found by cellAlongRay and the traverser's cells up to it skipped.
      const Eigen::Vector3d towards_camera = (c - p).normalized();
      const Delaunay::Cell_handle first = cellAlongRay(tr, v, toPoint(c));
      Delaunay::Segment_cell_iterator it(&tr, v, toPoint(c));
      const Delaunay::Segment_cell_iterator end = it.end();
      if (Delaunay::Cell_handle(it) != first) ++it;
      if (it != end && Delaunay::Cell_handle(it) == first) ++it;
      ++counts.cells_crossed;
      if (tr.is_infinite(first)) {
        evidence.source[first->info()] += w;
        continue;
      }
      Delaunay::Cell_handle previous = first;
      int steps = 1;
      for (; it != end; ++it) {
        const Delaunay::Cell_handle cell = it;
        ++counts.cells_crossed;
        {
          int f = -1;
          if (cell->has_neighbor(previous, f)) {
            // The facet's distance in front of the point, along the ray.
            double d = 0.0;
            if (options.noise_sigma > 0.0) {
              Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
              int finite = 0;
              for (int j = 0; j < 4; ++j) {
                if (j == f || tr.is_infinite(cell->vertex(j))) continue;
                centroid += toEigen(cell->vertex(j)->point());
                ++finite;
              }
              d = (centroid / std::max(finite, 1) - p).dot(towards_camera);
            }
            evidence.across[4 * cell->info() + f] += softWeight(w, d, options.noise_sigma);
          } else {
            ++counts.skipped_steps;
          }
        }
        if (tr.is_infinite(cell)) {
          // The ray has left the hull: this unbounded cell is free space.
          evidence.source[cell->info()] += w;
          break;
        }
        previous = cell;
        if (++steps >= options.max_cells_per_ray) {
          ++counts.cut_short;
          break;
        }
      }
    }
  }
  return counts;
}

void addPriorAndAreaTerms(const Delaunay& tr, const VisibilityPoints& points,
                          const SurfaceCutOptions& options, CellEvidence& evidence) {
  if (options.prior_weight > 0.0) {
    for (auto cell = tr.all_cells_begin(); cell != tr.all_cells_end(); ++cell) {
      const int node = cell->info();
      if (!tr.is_infinite(Delaunay::Cell_handle(cell))) {
        evidence.sink[node] += options.prior_weight;
        continue;
      }
      const int inf = cell->index(tr.infinite_vertex());
      const Delaunay::Cell_handle inner = cell->neighbor(inf);
      const Point& o = inner->vertex(inner->index(Delaunay::Cell_handle(cell)))->point();
      const Point& a = cell->vertex((inf + 1) & 3)->point();
      const Point& b = cell->vertex((inf + 2) & 3)->point();
      const Point& d = cell->vertex((inf + 3) & 3)->point();
      const CGAL::Orientation inner_side = CGAL::orientation(a, b, d, o);
      bool faces_camera = false;
      for (int j = 1; j <= 3 && !faces_camera; ++j) {
        const int point = cell->vertex((inf + j) & 3)->info();
        for (int k : points.views[point]) {
          const CGAL::Orientation side = CGAL::orientation(a, b, d, toPoint(points.c_W[k]));
          if (side != CGAL::COPLANAR && side != inner_side) {
            faces_camera = true;
            break;
          }
        }
      }
      (faces_camera ? evidence.source : evidence.sink)[node] += options.prior_weight;
    }
  }
  if (options.area_weight > 0.0) {
    for (auto facet = tr.finite_facets_begin(); facet != tr.finite_facets_end(); ++facet) {
      const Delaunay::Cell_handle cell = facet->first;
      const int f = facet->second;
      const Eigen::Vector3d a = toEigen(cell->vertex((f + 1) & 3)->point());
      const Eigen::Vector3d b = toEigen(cell->vertex((f + 2) & 3)->point());
      const Eigen::Vector3d d = toEigen(cell->vertex((f + 3) & 3)->point());
      const double cost = options.area_weight * 0.5 * (b - a).cross(d - a).norm();
      const Delaunay::Cell_handle other = cell->neighbor(f);
      // Hull facets are left free: facets between two unbounded cells have
      // no area to charge, so charging hull facets would let the cut hide
      // the surface at infinity by labelling unbounded cells matter.
      if (tr.is_infinite(cell) || tr.is_infinite(other)) continue;
      evidence.across[4 * cell->info() + f] += cost;
      evidence.across[4 * other->info() + other->index(cell)] += cost;
    }
  }
}

CutGraph toCutGraph(const Delaunay& tr, const CellEvidence& evidence) {
  CutGraph graph(static_cast<int>(evidence.source.size()));
  graph.source_capacity = evidence.source;
  graph.sink_capacity = evidence.sink;
  graph.links.reserve(tr.number_of_facets());
  for (auto facet = tr.all_facets_begin(); facet != tr.all_facets_end(); ++facet) {
    const Delaunay::Cell_handle cell = facet->first;
    const int f = facet->second;
    const Delaunay::Cell_handle other = cell->neighbor(f);
    const int g = other->index(cell);
    graph.links.push_back({cell->info(), other->info(), evidence.across[4 * cell->info() + f],
                           evidence.across[4 * other->info() + g]});
  }
  return graph;
}

}  // namespace hsmap::surface_detail
