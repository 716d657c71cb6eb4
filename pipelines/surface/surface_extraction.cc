#include "pipelines/surface/surface_extraction.h"

#include <algorithm>
#include <array>
#include <tuple>
#include <utility>

#include "pipelines/surface/delaunay_cells.h"

namespace hsmap {

using surface_detail::Delaunay;

SurfaceMesh extractSurface(const CellLabelling& labelling) {
  const surface_detail::LabelledDelaunay& cells = labelling.cells();
  const Delaunay& tr = cells.tr;
  std::vector<std::array<Delaunay::Vertex_handle, 3>> faces;
  for (auto facet = tr.finite_facets_begin(); facet != tr.finite_facets_end(); ++facet) {
    const Delaunay::Cell_handle cell = facet->first;
    const int f = facet->second;
    const Delaunay::Cell_handle other = cell->neighbor(f);
    const bool inside = cells.inside[cell->info()] != 0;
    if (inside == (cells.inside[other->info()] != 0)) continue;
    // Orient towards the free-space cell: (b - a) x (c - a) must point at
    // its opposite vertex, or away from the matter cell's one when the
    // free-space cell is unbounded (exact predicate, so flat facets are safe).
    const Delaunay::Cell_handle inner = inside ? cell : other;
    const Delaunay::Cell_handle outer = inside ? other : cell;
    const int f_inner = inside ? f : other->index(cell);
    std::array<Delaunay::Vertex_handle, 3> face = {inner->vertex((f_inner + 1) & 3),
                                                   inner->vertex((f_inner + 2) & 3),
                                                   inner->vertex((f_inner + 3) & 3)};
    const bool use_outer = !tr.is_infinite(outer);
    const Delaunay::Vertex_handle probe =
        use_outer ? outer->vertex(outer->index(inner)) : inner->vertex(f_inner);
    const CGAL::Orientation side = CGAL::orientation(face[0]->point(), face[1]->point(),
                                                     face[2]->point(), probe->point());
    if ((side == CGAL::POSITIVE) != use_outer) std::swap(face[1], face[2]);
    faces.push_back(face);
  }
  // The facet iterator visits each facet from the cell of lower address, so
  // the faces came out in an order (and the mesh's vertices after cleaning
  // and stitching in one) that changed from run to run. Each face is turned
  // to start at its lowest input point (a cyclic turn: the orientation
  // stays) and the faces are sorted by their points: the same cut gives the
  // same mesh, byte for byte.
  for (auto& face : faces) {
    const auto lowest = std::min_element(face.begin(), face.end(), [](const auto& a, const auto& b) {
      return a->info() < b->info();
    });
    std::rotate(face.begin(), lowest, face.end());
  }
  std::sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) {
    return std::tuple(a[0]->info(), a[1]->info(), a[2]->info()) < std::tuple(b[0]->info(), b[1]->info(), b[2]->info());
  });
  // Dense re-indexing in input-point order.
  std::vector<std::pair<int, Delaunay::Vertex_handle>> used;
  for (const auto& face : faces)
    for (const auto& v : face) used.emplace_back(v->info(), v);
  std::sort(used.begin(), used.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  used.erase(std::unique(used.begin(), used.end(),
                         [](const auto& a, const auto& b) { return a.first == b.first; }),
             used.end());
  SurfaceMesh mesh;
  mesh.vertices.reserve(used.size());
  mesh.point_index.reserve(used.size());
  for (const auto& [index, v] : used) {
    mesh.point_index.push_back(index);
    mesh.vertices.emplace_back(v->point().x(), v->point().y(), v->point().z());
  }
  auto dense = [&](const Delaunay::Vertex_handle& v) {
    const auto it = std::lower_bound(used.begin(), used.end(), v->info(),
                                     [](const auto& a, int key) { return a.first < key; });
    return static_cast<int>(it - used.begin());
  };
  mesh.triangles.reserve(faces.size());
  for (const auto& face : faces) mesh.triangles.emplace_back(dense(face[0]), dense(face[1]), dense(face[2]));
  return mesh;
}

}  // namespace hsmap
