#pragma once
// Ray and RayHit: the plain values MeshRayCaster (mesh_ray_caster.h) reads and
// writes. Everything is double precision and in the frame of the mesh (the
// simulator uses the world frame W, local NED, metres).
//
// A ray is the segment origin + t * direction for t in [t_near, t_far].
// `direction` must have unit length, so that t and RayHit::distance are metres;
// the caster only checks that with a debug assert (normalising every ray
// would cost time on the hot path and hide caller bugs in release builds).
// t_near must be >= 0; t_far < t_near is an empty segment (always a miss).

#include <Eigen/Core>
#include <limits>

namespace hsmap {

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();    // unit length
  double t_near = 0.0;                                     // metres, >= 0
  double t_far = std::numeric_limits<double>::infinity();  // metres
};

struct RayHit {
  // Metres along the ray to the hit: origin + distance * direction.
  double distance = std::numeric_limits<double>::infinity();
  // Index into the mesh's triangle list; -1 for a miss.
  int triangle = -1;
  // Barycentric weights of the triangle's 2nd and 3rd vertex at the hit; the
  // 1st vertex has weight 1 - u - v. Always u, v >= 0 and u + v <= 1.
  double u = 0.0;
  double v = 0.0;
  // Unit geometric (face) normal of the hit triangle, turned to face the ray
  // origin (normal . direction <= 0), whatever the triangle's winding.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();

  bool hit() const { return triangle >= 0; }
};

}  // namespace hsmap
