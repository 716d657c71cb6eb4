#pragma once
// TriangleMeshDistance: the Euclidean distance from points to a triangle
// mesh (the nearest point of any triangle, interior, edge or vertex), for the
// mesh metrics of `hsmap evaluate` (mesh_metrics.h).
//
// The queries go through CGAL's AABB tree (CGAL::AABB_tree over the
// triangles, with its k-d tree of hint points for closest-point queries:
// Alliez, Tayeb and Wormser, "3D Fast Intersection and Distance Computation",
// CGAL User and Reference Manual), in double precision: at a few hundred
// metres from W's origin a double resolves ~1e-13 m, far below the 2 cm of
// mesh_completeness. Embree's point query would work in float, which at that
// range resolves only ~3e-5 m.
//
// Degenerate triangles (three collinear or coincident vertices) are left out:
// they have no area, and their edges are edges of neighbouring triangles in
// any mesh a surface stage writes. Unreferenced vertices play no part.
//
// Threads: the tree and its k-d tree are built in the constructor, so the
// const queries are thread-safe; distances() runs its points in parallel
// (TBB).
//
// Errors: std::invalid_argument for a triangle index out of range, a
// non-finite vertex used by a triangle, or a mesh with no non-degenerate
// triangle (there is nothing to measure a distance to).

#include <memory>
#include <vector>

#include <Eigen/Core>

namespace hsmap {

class TriangleMeshDistance {
 public:
  TriangleMeshDistance(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<Eigen::Vector3i>& triangles);
  ~TriangleMeshDistance();
  TriangleMeshDistance(const TriangleMeshDistance&) = delete;
  TriangleMeshDistance& operator=(const TriangleMeshDistance&) = delete;

  // Distance (m, in the mesh's frame) from `point` to the nearest point of the mesh;
  // std::invalid_argument for a non-finite point.
  double distance(const Eigen::Vector3d& point) const;
  // distances[i] = distance(points[i]), computed in parallel.
  std::vector<double> distances(const std::vector<Eigen::Vector3d>& points) const;

  // Triangles in the tree (the non-degenerate ones).
  std::size_t triangleCount() const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace hsmap
