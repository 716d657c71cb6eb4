#pragma once
// The surface stage's triangle mesh: vertices and triangles indexing them,
// each triangle's vertices counter-clockwise seen from outside, so that
// (v1 - v0) x (v2 - v0) points out of the matter, towards the free space.

#include <vector>

#include <Eigen/Core>

namespace hsmap {

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  // Per vertex, the index of the input point it is (VisibilityPoints::p_W).
  std::vector<int> point_index;
};

}  // namespace hsmap
