#pragma once
// MeshRayCaster: first-hit and occlusion queries of rays against a static
// triangle mesh, with Embree 3 doing the BVH build and traversal.
//
// Frames and units: the mesh and the rays are in one frame (the simulator
// uses W, local NED, metres); ray directions are unit vectors (ray.h).
//
// Precision. Embree works in float, which at a few hundred metres from the
// origin resolves only ~3e-5 m. So the caster
//   1. stores the vertices in float RELATIVE to the centre of the mesh's
//      bounding box (sceneOffset()) and moves ray origins by the same offset,
//      in double, before rounding them to float; and
//   2. lets Embree pick the hit triangle, then recomputes the distance and
//      the barycentrics in double against that triangle's vertices
//      (triangle_plane_hit.h), so origin + distance * direction lies on the
//      triangle's plane to ~1e-12 m relative to the scene size.
// Whether a ray hits at all, and whether a hit lies inside [t_near, t_far],
// is decided by Embree in float: a surface within ~1e-6 (relative) of either
// end of the segment, or a ray grazing the mesh's outer boundary, may go
// either way. The double distance is reported as computed, so it can lie
// outside [t_near, t_far] by that much. For a ray almost parallel to the hit
// triangle (the double distance differs from Embree's by more than 1e-4 of
// the ray's length scale) the plane intersection is ill-conditioned and
// Embree's float result is kept instead. Rays that start ON the mesh (from an
// earlier hit) should use a t_near of a few millimetres so as not to find the
// surface they start from.
//
// Ties: where triangles meet (a ray through a shared edge or vertex), Embree
// returns any of them, and which one can differ between its single-ray and
// packet code and even with the other rays of a packet. When the double hit
// point lies on the boundary of Embree's triangle, the caster therefore
// re-tests every triangle sharing a vertex with it and reports the one that
// contains the point with the smallest (distance, triangle index). A hit is
// thus a function of the ray and the mesh alone -- the same in a batch as
// alone, whatever the batch and thread count -- except in the float cases
// above (grazing rays, segment ends, the outer boundary) and for overlapping
// triangles that share no vertex.
//
// Triangles are two-sided; RayHit::normal is the unit face normal turned to
// face the ray origin, and u, v are clamped into the triangle (u, v >= 0,
// u + v <= 1; the clamp moves them by at most rounding error for a proper hit).
//
// Threads: queries are const and thread-safe; run batches in parallel (TBB).
// The constructor builds the BVH with Embree's TBB tasks, so it uses the
// threads that tbb::global_control allows.
//
// Errors: the constructor throws std::invalid_argument for an empty triangle
// list, a vertex index out of range or a non-finite vertex; queries throw
// std::invalid_argument for a ray with a non-finite origin or direction, a
// t_near that is negative or NaN, or a NaN t_far; Embree's own errors become
// std::runtime_error (embree_device.h).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/raycast/ray.h"

namespace hsmap {

class MeshRayCaster {
 public:
  // Copies the mesh (in double, for the refinement), builds the BVH and
  // precomputes the unit face normals and the vertex-to-triangle lists used
  // to break ties: besides Embree's BVH, ~28 bytes per vertex and ~50 per
  // triangle.
  // Every triangle index must be in [0, vertices.size()). Vertices that no
  // triangle uses are allowed (they are not part of bounds()).
  MeshRayCaster(const std::vector<Eigen::Vector3d>& vertices,
                const std::vector<Eigen::Vector3i>& triangles);
  ~MeshRayCaster();
  MeshRayCaster(const MeshRayCaster&) = delete;
  MeshRayCaster& operator=(const MeshRayCaster&) = delete;
  // A moved-from caster may only be destroyed or assigned to.
  MeshRayCaster(MeshRayCaster&&) noexcept;
  MeshRayCaster& operator=(MeshRayCaster&&) noexcept;

  // The nearest hit in [ray.t_near, ray.t_far], or a RayHit with hit() false.
  RayHit intersect(const Ray& ray) const;

  // hits[i] = intersect(rays[i]), bit for bit (see "Ties" above); the sizes
  // must match (std::invalid_argument otherwise). Uses Embree's ray streams,
  // tuned for COHERENT batches (neighbouring rays with similar origins and
  // directions, e.g. an image's pixels in row order): 3.4x the single-ray
  // rate for camera rays, the same rate as single rays for scattered ones
  // (benchmarks/raycast_bench.cc).
  // Sequential and allocation-free: callers parallelise over batches.
  void intersect(std::span<const Ray> rays, std::span<RayHit> hits) const;

  // Whether any triangle is hit in [ray.t_near, ray.t_far]. Cheaper than
  // intersect() (stops at the first hit found); agrees with intersect().hit().
  bool occluded(const Ray& ray) const;
  // occluded[i] = occluded(rays[i]) (1 or 0); the sizes must match
  // (std::invalid_argument otherwise). Sequential, like the batch intersect().
  void occluded(std::span<const Ray> rays, std::span<std::uint8_t> occluded) const;

  // Axis-aligned box of the vertices the triangles use.
  Eigen::AlignedBox3d bounds() const;
  // The point subtracted from every vertex before Embree stores it in float
  // (the centre of bounds()).
  const Eigen::Vector3d& sceneOffset() const;
  std::size_t triangleCount() const;
  const std::vector<Eigen::Vector3d>& vertices() const;
  const std::vector<Eigen::Vector3i>& triangles() const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace hsmap
