#pragma once
// Double-precision intersection of a ray's LINE with the PLANE of one triangle,
// used to refine Embree's single-precision hits (mesh_ray_caster.h).
//
// Embree decides WHICH triangle a ray hits, in float. This function then
// recomputes WHERE, in double, by the Moller-Trumbore algorithm (Moller &
// Trumbore, "Fast, minimum storage ray-triangle intersection", JGT 1997):
// with e1 = b - a, e2 = c - a, p = d x e2, det = e1 . p, s = o - a, q = s x e1,
//   t = (e2 . q) / det,   u = (s . p) / det,   v = (d . q) / det,
// the point o + t d is the intersection of the line with the triangle's plane
// and equals (1 - u - v) a + u b + v c. Unlike the textbook algorithm it does
// not reject points outside the triangle or behind the origin: the triangle is
// already known to be hit, and a hit on an edge may give u or v of about -1e-7
// from rounding, which the caller clamps.
//
// Returns false (leaving *hit untouched) when the line is parallel to the
// plane or the triangle is degenerate, i.e. when det is zero or the results
// are not finite.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross
#include <cmath>

namespace hsmap {

struct TrianglePlaneHit {
  double t = 0.0;  // along the ray direction (metres if it is a unit vector)
  double u = 0.0;  // barycentric weight of b
  double v = 0.0;  // barycentric weight of c
};

inline bool intersectTrianglePlane(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c, TrianglePlaneHit* hit) {
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return false;
  const double inverse_det = 1.0 / det;
  // Subtracting a first keeps the products small when the mesh is far from the
  // frame origin (hundreds of metres), which is where double precision is lost.
  const Eigen::Vector3d s = origin - a;
  const Eigen::Vector3d q = s.cross(e1);
  const double t = e2.dot(q) * inverse_det;
  const double u = s.dot(p) * inverse_det;
  const double v = direction.dot(q) * inverse_det;
  if (!(std::isfinite(t) && std::isfinite(u) && std::isfinite(v))) return false;
  hit->t = t;
  hit->u = u;
  hit->v = v;
  return true;
}

}  // namespace hsmap
