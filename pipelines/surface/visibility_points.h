#pragma once
// The surface stage's input: fused dense points, each with the camera
// centres that saw it. Every (point, camera) pair is one visibility ray
// c -> p: the segment between them is free space, and the space just beyond
// p along the ray is matter (Labatut et al. 2009, "Robust and efficient
// surface reconstruction from range data", section 3).
//
// All in the world frame W. Cameras are stored once and referenced by index,
// because a dense cloud has many points per camera.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace hsmap {

struct VisibilityPoints {
  std::vector<Eigen::Vector3d> p_W;             // the points
  std::vector<std::vector<int>> views;          // per point: indices into c_W
  std::vector<Eigen::Vector3d> c_W;             // camera centres
  std::vector<double> weights;                  // empty (all 1) or one per point, > 0

  // Empty when the points are usable, otherwise what is wrong (the first
  // problem found): counts that do not match, a camera index out of range,
  // a non-finite coordinate, a weight <= 0, a camera at its point.
  std::string validate() const;
  double weight(std::size_t i) const { return weights.empty() ? 1.0 : weights[i]; }
};

}  // namespace hsmap
