#include "pipelines/surface/cell_labelling.h"

#include <chrono>
#include <stdexcept>
#include <utility>

#include "core/util/stage_timer.h"
#include "pipelines/surface/delaunay_cells.h"
#include "pipelines/surface/min_cut.h"
#include "pipelines/surface/visibility_evidence.h"

namespace hsmap {

using surface_detail::Delaunay;
using surface_detail::LabelledDelaunay;
using surface_detail::Point;

CellLabelling::CellLabelling(std::shared_ptr<const LabelledDelaunay> cells)
    : cells_(std::move(cells)) {}

bool CellLabelling::isInside(const Eigen::Vector3d& x) const {
  const Delaunay::Cell_handle cell = cells_->tr.locate(Point(x.x(), x.y(), x.z()));
  return cells_->inside[cell->info()] != 0;
}

CellLabelling labelCells(const VisibilityPoints& points, const SurfaceCutOptions& options,
                         SurfaceCutReport* report) {
  if (std::string problem = points.validate(); !problem.empty())
    throw std::invalid_argument("surface: visibility points: " + problem);
  if (std::string problem = options.validate(); !problem.empty())
    throw std::invalid_argument("surface: options: " + problem);
  const auto start = std::chrono::steady_clock::now();
  SurfaceCutReport r;
  r.points = static_cast<std::int64_t>(points.p_W.size());

  auto labelled = std::make_shared<LabelledDelaunay>();
  Delaunay& tr = labelled->tr;
  {
    std::vector<std::pair<Point, int>> indexed;
    indexed.reserve(points.p_W.size());
    for (std::size_t i = 0; i < points.p_W.size(); ++i) {
      const Eigen::Vector3d& p = points.p_W[i];
      indexed.emplace_back(Point(p.x(), p.y(), p.z()), static_cast<int>(i));
    }
    tr.insert(indexed.begin(), indexed.end());  // spatially sorted by CGAL
  }
  if (tr.dimension() < 3)
    throw std::runtime_error("surface: the " + std::to_string(points.p_W.size()) +
                             " points span no volume (all on one plane, line or point), so "
                             "there are no cells to label");
  // Each input point's vertex; a point that repeats another is the vertex
  // that was kept.
  std::vector<Delaunay::Vertex_handle> vertex_of_point(points.p_W.size());
  for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v)
    vertex_of_point[v->info()] = v;
  for (std::size_t i = 0; i < points.p_W.size(); ++i) {
    if (vertex_of_point[i] != Delaunay::Vertex_handle()) continue;
    Delaunay::Locate_type lt;
    int li = 0, lj = 0;
    const Eigen::Vector3d& p = points.p_W[i];
    const Delaunay::Cell_handle cell = tr.locate(Point(p.x(), p.y(), p.z()), lt, li, lj);
    if (lt != Delaunay::VERTEX)
      throw std::logic_error("surface: an input point is neither a vertex nor a duplicate of one");
    vertex_of_point[i] = cell->vertex(li);
  }
  int node = 0;
  for (auto cell = tr.all_cells_begin(); cell != tr.all_cells_end(); ++cell) cell->info() = node++;
  r.vertices = static_cast<std::int64_t>(tr.number_of_vertices());
  r.cells = node;
  r.finite_cells = static_cast<std::int64_t>(tr.number_of_finite_cells());
  r.seconds_triangulation = secondsSince(start);

  const auto rays_start = std::chrono::steady_clock::now();
  surface_detail::CellEvidence evidence(node);
  const surface_detail::RayCounts counts =
      surface_detail::addVisibilityEvidence(tr, points, vertex_of_point, options, evidence);
  surface_detail::addPriorAndAreaTerms(tr, points, options, evidence);
  r.rays = counts.rays;
  r.rays_cut_short = counts.cut_short;
  r.cells_crossed = counts.cells_crossed;
  r.skipped_steps = counts.skipped_steps;
  r.grazing_rays = counts.grazing;
  r.seconds_rays = secondsSince(rays_start);

  const auto cut_start = std::chrono::steady_clock::now();
  MinCut cut = solveMinCut(surface_detail::toCutGraph(tr, evidence));
  labelled->inside = std::move(cut.inside);
  r.flow = cut.flow;
  for (char inside : labelled->inside) r.inside_cells += inside;
  r.seconds_cut = secondsSince(cut_start);
  r.seconds_total = secondsSince(start);
  if (report) *report = r;
  return CellLabelling(std::move(labelled));
}

}  // namespace hsmap
