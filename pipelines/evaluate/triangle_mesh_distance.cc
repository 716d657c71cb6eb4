#include "pipelines/evaluate/triangle_mesh_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

// Plain double arithmetic: closest-point queries only compare and measure
// distances, where exact predicates would buy nothing but time.
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle3 = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using AabbTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 toCgal(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

struct TriangleMeshDistance::Tree {
  // The primitives refer to these triangles by iterator: the vector must not
  // move or grow once the tree is built.
  std::vector<Triangle3> triangles;
  AabbTree tree;
};

TriangleMeshDistance::TriangleMeshDistance(const std::vector<Eigen::Vector3d>& vertices,
                                           const std::vector<Eigen::Vector3i>& triangles)
    : tree_(std::make_unique<Tree>()) {
  const auto vertex_count = static_cast<long long>(vertices.size());
  tree_->triangles.reserve(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Eigen::Vector3i& triangle = triangles[f];
    for (int k = 0; k < 3; ++k) {
      if (triangle[k] < 0 || triangle[k] >= vertex_count) {
        throw std::invalid_argument("TriangleMeshDistance: triangle " + std::to_string(f) +
                                    " has vertex index " + std::to_string(triangle[k]) +
                                    ", expected one in [0, " + std::to_string(vertex_count) + ")");
      }
      if (!vertices[triangle[k]].allFinite()) {
        throw std::invalid_argument("TriangleMeshDistance: vertex " + std::to_string(triangle[k]) +
                                    " of triangle " + std::to_string(f) + " is not finite");
      }
    }
    const Triangle3 t(toCgal(vertices[triangle[0]]), toCgal(vertices[triangle[1]]),
                      toCgal(vertices[triangle[2]]));
    if (!t.is_degenerate()) tree_->triangles.push_back(t);
  }
  if (tree_->triangles.empty()) {
    throw std::invalid_argument(
        "TriangleMeshDistance: the mesh has no triangle with an area to measure distances to");
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  // Both trees now, not lazily at the first query: the queries of
  // distances() then only read them.
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

TriangleMeshDistance::~TriangleMeshDistance() = default;

double TriangleMeshDistance::distance(const Eigen::Vector3d& point) const {
  // CGAL's traversal compares distances: a NaN would make it return any triangle.
  if (!point.allFinite()) {
    throw std::invalid_argument("TriangleMeshDistance: a query point is not finite");
  }
  return std::sqrt(tree_->tree.squared_distance(toCgal(point)));
}

std::vector<double> TriangleMeshDistance::distances(
    const std::vector<Eigen::Vector3d>& points) const {
  std::vector<double> out(points.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        out[i] = distance(points[i]);
                      }
                    });
  return out;
}

std::size_t TriangleMeshDistance::triangleCount() const { return tree_->triangles.size(); }

}  // namespace hsmap
