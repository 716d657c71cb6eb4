#pragma once
// The 3D Delaunay tetrahedralisation the surface stage labels, and its
// labels. Internal to pipelines/surface: the public headers keep CGAL out.
//
// Kernel: exact predicates, inexact constructions (the walk along rays and
// the triangulation only need predicates to be exact). Vertex info: the
// index of the input point; cell info: the cell's node in the cut graph,
// numbered over all cells, the unbounded ones (incident to the infinite
// vertex) included, since matter and free space extend past the hull.

#include <vector>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

namespace hsmap::surface_detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using CellBase = CGAL::Triangulation_cell_base_with_info_3<
    int, Kernel, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
using Tds = CGAL::Triangulation_data_structure_3<VertexBase, CellBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
using Point = Kernel::Point_3;

struct LabelledDelaunay {
  Delaunay tr;
  std::vector<char> inside;  // per cell node (cell->info()): 1 = matter
};

}  // namespace hsmap::surface_detail
