#pragma once
// Rock meshes for the simulated seabed: closed, star-shaped triangle meshes
// made from a subdivided icosahedron whose vertices are pushed in or out
// along their direction from the centre.
//
// Shape of a rock, in its own frame R (centre at the origin): for a unit
// direction d of the icosphere,
//   r(d) = min(1 + roughness * n(d), cuts(d)) * (1 + 0.03 * n_fine(d))
//   v_R  = semi_axes .* (r(d) * d)
// where n is seeded fractal 3D noise (|n| < 0.87) and cuts(d) the distance
// along d to the nearest of a few random planes 0.65-0.9 from the centre:
// the planes give the flat faces and edges of broken rock. r(d) > 0 for every
// d, so the surface stays star-shaped around the centre: closed, with no
// self-intersection, every triangle wound counter-clockwise seen from
// outside (outward normals (b - a) x (c - a)).
//
// makeRockMesh returns the vertices rotated into W (q_W_R) but NOT translated:
// p_W = centre_W + vertex. Callers place the rock after looking at its extent
// (seabed_scene.cc sinks it into the seabed).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace hsmap {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
};

// Unit sphere: the icosahedron with each triangle split into 4, `subdivisions`
// times (20 * 4^s triangles, 10 * 4^s + 2 vertices). Throws
// std::invalid_argument unless 0 <= subdivisions <= 7.
TriangleMesh makeIcosphere(int subdivisions);

struct RockShape {
  Eigen::Vector3d semi_axes_m{0.3, 0.3, 0.2};  // in R, before the displacement
  Eigen::Quaterniond q_W_R = Eigen::Quaterniond::Identity();
  double roughness = 0.25;  // relative amplitude of the noise displacement
  int planar_cuts = 4;      // flat faces (0 for a rounded rock)
  std::uint64_t seed = 0;
};

// The rock, displaced from `unit_sphere` (a makeIcosphere result; it is only
// read, so one sphere serves every rock of a scene). Throws
// std::invalid_argument for non-positive semi-axes, roughness outside [0, 0.9]
// or negative planar_cuts.
TriangleMesh makeRockMesh(const RockShape& shape, const TriangleMesh& unit_sphere);

}  // namespace hsmap
