#include "core/raycast/mesh_ray_caster.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cassert>
#include <climits>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/raycast/embree_device.h"
#include "core/raycast/triangle_plane_hit.h"

namespace hsmap {

namespace {

// The double plane intersection replaces Embree's float distance only if the
// two agree to this fraction of the ray's length scale (1 m + distance of the
// origin from the scene offset + hit distance, the magnitudes float rounding
// is relative to). They disagree by more only for rays within ~1e-3 rad of
// the triangle's plane, where the plane intersection is ill-conditioned.
constexpr double kRefinementTolerance = 1e-4;

// A double hit point whose smallest barycentric weight is within this of 0 is
// on the triangle's boundary (rounding of the weights is ~1e-16 times the
// ratio of coordinates to triangle size, far below it).
constexpr double kOnBoundary = 1e-9;

double minWeight(const TrianglePlaneHit& hit) {
  return std::min({1.0 - hit.u - hit.v, hit.u, hit.v});
}

[[noreturn]] void throwInvalidRay(const Ray& ray) {
  auto vector = [](const Eigen::Vector3d& x) {
    return "(" + std::to_string(x.x()) + ", " + std::to_string(x.y()) + ", " +
           std::to_string(x.z()) + ")";
  };
  throw std::invalid_argument(
      "MeshRayCaster: expected a ray with a finite origin (within float range of the mesh) and "
      "direction, 0 <= t_near and a t_far that is not NaN; got origin " +
      vector(ray.origin) + ", direction " + vector(ray.direction) + ", t_near " +
      std::to_string(ray.t_near) + ", t_far " + std::to_string(ray.t_far));
}

// Fills Embree's float ray, with the origin moved into the scene's offset
// frame. Returns false for an empty segment (t_far < t_near), which is a miss
// without asking Embree. Throws for rays Embree cannot trace (this Embree
// build does not ignore invalid rays; NaNs could corrupt its traversal).
inline bool toEmbreeRay(const Ray& ray, const Eigen::Vector3d& scene_offset, RTCRay* out) {
  assert(std::abs(ray.direction.squaredNorm() - 1.0) < 1e-6 && "Ray::direction must be unit");
  const Eigen::Vector3d origin = ray.origin - scene_offset;
  out->org_x = static_cast<float>(origin.x());
  out->org_y = static_cast<float>(origin.y());
  out->org_z = static_cast<float>(origin.z());
  out->dir_x = static_cast<float>(ray.direction.x());
  out->dir_y = static_cast<float>(ray.direction.y());
  out->dir_z = static_cast<float>(ray.direction.z());
  const bool valid = std::isfinite(out->org_x) && std::isfinite(out->org_y) &&
                     std::isfinite(out->org_z) && std::isfinite(out->dir_x) &&
                     std::isfinite(out->dir_y) && std::isfinite(out->dir_z) && ray.t_near >= 0.0 &&
                     !std::isnan(ray.t_far);
  if (!valid) [[unlikely]] {
    throwInvalidRay(ray);
  }
  if (ray.t_far < ray.t_near) return false;
  out->tnear = static_cast<float>(ray.t_near);
  out->tfar = static_cast<float>(ray.t_far);  // > FLT_MAX becomes +inf
  out->time = 0.0f;
  out->mask = 0xFFFFFFFFu;
  out->id = 0;
  out->flags = 0;
  return true;
}

}  // namespace

struct MeshRayCaster::Scene {
  // Declared first so that it is destroyed last, after the scene.
  EmbreeDevice device;
  RTCScene handle = nullptr;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
  Eigen::AlignedBox3d bounds;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  // Triangles around each vertex (compressed rows): the triangles of vertex
  // i are vertex_triangles[vertex_triangle_begin[i] .. [i + 1]).
  std::vector<int> vertex_triangle_begin;
  std::vector<int> vertex_triangles;
  // Unit face normal of each triangle, (b - a) x (c - a) normalised; zero for
  // a triangle degenerate in double. Precomputed: normalising per hit (a
  // square root and divisions) took a quarter of the refinement's time.
  std::vector<Eigen::Vector3d> normals;

  Scene() = default;
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;
  ~Scene() {
    if (handle != nullptr) rtcReleaseScene(handle);
  }

  void computeNormals() {
    normals.resize(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const Eigen::Vector3i& f = triangles[t];
      const Eigen::Vector3d& a = vertices[f[0]];
      const Eigen::Vector3d n = (vertices[f[1]] - a).cross(vertices[f[2]] - a);
      const double length = n.norm();
      normals[t] = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
    }
  }

  void buildVertexTriangles() {
    vertex_triangle_begin.assign(vertices.size() + 1, 0);
    for (const Eigen::Vector3i& f : triangles) {
      for (int k = 0; k < 3; ++k) ++vertex_triangle_begin[f[k] + 1];
    }
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      vertex_triangle_begin[i + 1] += vertex_triangle_begin[i];
    }
    vertex_triangles.resize(3 * triangles.size());
    std::vector<int> next(vertex_triangle_begin.begin(), vertex_triangle_begin.end() - 1);
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) vertex_triangles[next[triangles[t][k]]++] = static_cast<int>(t);
    }
  }

  // Double-precision plane hit of triangle `index`, accepted only if it is
  // within `window` of Embree's float distance (see kRefinementTolerance).
  bool planeHitNear(int index, const Ray& ray, double t_embree, double window,
                    TrianglePlaneHit* hit) const {
    const Eigen::Vector3i& f = triangles[index];
    return intersectTrianglePlane(ray.origin, ray.direction, vertices[f[0]], vertices[f[1]],
                                  vertices[f[2]], hit) &&
           std::abs(hit->t - t_embree) <= window;
  }

  // Turns Embree's float hit into a RayHit recomputed in double (see the
  // header), with ties between triangles broken canonically.
  RayHit refine(const Ray& ray, const RTCRayHit& embree) const {
    const double t_embree = embree.ray.tfar;
    // The max-norm stands in for the Euclidean one (within sqrt(3)), without
    // a square root.
    const double window =
        kRefinementTolerance *
        (1.0 + (ray.origin - offset).lpNorm<Eigen::Infinity>() + std::abs(t_embree));
    int best = static_cast<int>(embree.hit.primID);
    TrianglePlaneHit best_hit;
    if (!planeHitNear(best, ray, t_embree, window, &best_hit)) {
      // Ill-conditioned (ray almost parallel to the triangle): keep Embree's.
      best_hit = {t_embree, embree.hit.u, embree.hit.v};
    } else if (minWeight(best_hit) <= kOnBoundary) {
      // The point is on (or, by float rounding, just outside) the boundary of
      // Embree's triangle, where Embree's single-ray and packet traversals
      // may pick different triangles of the ones meeting there, depending
      // even on the other rays of a packet. Choose among all triangles that
      // share a vertex with it -- a set that contains every triangle meeting
      // at the point -- the one containing the point with the smallest
      // (distance, index): a choice that depends on the ray alone.
      const Eigen::Vector3i& f = triangles[best];
      int chosen = -1;
      TrianglePlaneHit chosen_hit;
      for (int k = 0; k < 3; ++k) {
        for (int i = vertex_triangle_begin[f[k]]; i < vertex_triangle_begin[f[k] + 1]; ++i) {
          const int candidate = vertex_triangles[i];
          TrianglePlaneHit candidate_hit;
          if (!planeHitNear(candidate, ray, t_embree, window, &candidate_hit) ||
              minWeight(candidate_hit) < -kOnBoundary) {
            continue;
          }
          if (chosen < 0 || candidate_hit.t < chosen_hit.t ||
              (candidate_hit.t == chosen_hit.t && candidate < chosen)) {
            chosen = candidate;
            chosen_hit = candidate_hit;
          }
        }
      }
      // None: a ray past the mesh's outer boundary that float called a hit.
      if (chosen >= 0) {
        best = chosen;
        best_hit = chosen_hit;
      }
    }
    const Eigen::Vector3d embree_normal(embree.hit.Ng_x, embree.hit.Ng_y, embree.hit.Ng_z);
    return makeHit(ray, best, best_hit, embree_normal);
  }

  RayHit makeHit(const Ray& ray, int index, const TrianglePlaneHit& plane,
                 const Eigen::Vector3d& embree_normal) const {
    RayHit hit;
    hit.triangle = index;
    hit.distance = plane.t;
    // Clamp into the triangle: rounding on a shared edge gives ~-1e-16 and
    // float decisions near the outer boundary ~-1e-6.
    double u = std::max(plane.u, 0.0);
    double v = std::max(plane.v, 0.0);
    const double sum = u + v;
    if (sum > 1.0) {
      u /= sum;
      v /= sum;
    }
    hit.u = u;
    hit.v = v;
    Eigen::Vector3d normal = normals[index];
    if (normal.x() == 0.0 && normal.y() == 0.0 && normal.z() == 0.0) [[unlikely]] {
      // Collinear in double but not after rounding to float (only Embree's
      // own triangle can be like that: a candidate above had det != 0).
      normal = embree_normal.normalized();
    }
    if (normal.dot(ray.direction) > 0.0) normal = -normal;
    hit.normal = normal;
    return hit;
  }

  RayHit intersect(const Ray& ray) const {
    alignas(16) RTCRayHit embree;
    if (!toEmbreeRay(ray, offset, &embree.ray)) return RayHit{};
    embree.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    embree.hit.primID = RTC_INVALID_GEOMETRY_ID;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcIntersect1(handle, &context, &embree);
    throwIfEmbreeError("rtcIntersect1");
    if (embree.hit.geomID == RTC_INVALID_GEOMETRY_ID) return RayHit{};
    return refine(ray, embree);
  }
};

MeshRayCaster::MeshRayCaster(const std::vector<Eigen::Vector3d>& vertices,
                             const std::vector<Eigen::Vector3i>& triangles) {
  if (triangles.empty()) {
    throw std::invalid_argument("MeshRayCaster: expected at least one triangle, got none");
  }
  if (triangles.size() > static_cast<std::size_t>(INT_MAX)) {
    throw std::invalid_argument("MeshRayCaster: expected at most " + std::to_string(INT_MAX) +
                                " triangles, got " + std::to_string(triangles.size()));
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      throw std::invalid_argument("MeshRayCaster: vertex " + std::to_string(i) +
                                  " has a non-finite coordinate; expected finite x, y, z");
    }
  }
  auto scene = std::make_unique<Scene>();
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const int index = triangles[i][k];
      if (index < 0 || static_cast<std::size_t>(index) >= vertices.size()) {
        throw std::invalid_argument("MeshRayCaster: triangle " + std::to_string(i) +
                                    " has vertex index " + std::to_string(index) +
                                    "; expected an index in [0, " +
                                    std::to_string(vertices.size()) + ")");
      }
      scene->bounds.extend(vertices[index]);
    }
  }
  scene->vertices = vertices;
  scene->triangles = triangles;
  scene->offset = scene->bounds.center();
  scene->buildVertexTriangles();
  scene->computeNormals();

  const RTCDevice device = scene->device.get();
  scene->handle = rtcNewScene(device);
  throwIfEmbreeError("rtcNewScene");
  // ROBUST: watertight traversal, so that rays through the shared edges and
  // corners of a height field never slip between its triangles.
  rtcSetSceneFlags(scene->handle, RTC_SCENE_FLAG_ROBUST);
  // A static scene traced by millions of rays: spend time on a better BVH.
  rtcSetSceneBuildQuality(scene->handle, RTC_BUILD_QUALITY_HIGH);
  throwIfEmbreeError("rtcSetSceneBuildQuality");

  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  throwIfEmbreeError("rtcNewGeometry");
  // Releases our reference on every path; the scene keeps its own.
  struct GeometryReference {
    RTCGeometry geometry;
    ~GeometryReference() { rtcReleaseGeometry(geometry); }
  } reference{geometry};
  rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
  // rtcSetNewGeometryBuffer pads the vertex buffer for Embree's 16-byte loads.
  auto* vertex_buffer = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  throwIfEmbreeError("rtcSetNewGeometryBuffer(vertex)");
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d p = vertices[i] - scene->offset;
    vertex_buffer[3 * i + 0] = static_cast<float>(p.x());
    vertex_buffer[3 * i + 1] = static_cast<float>(p.y());
    vertex_buffer[3 * i + 2] = static_cast<float>(p.z());
  }
  auto* index_buffer = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), triangles.size()));
  throwIfEmbreeError("rtcSetNewGeometryBuffer(index)");
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) index_buffer[3 * i + k] = static_cast<unsigned>(triangles[i][k]);
  }
  rtcCommitGeometry(geometry);
  throwIfEmbreeError("rtcCommitGeometry");
  rtcAttachGeometry(scene->handle, geometry);
  throwIfEmbreeError("rtcAttachGeometry");
  rtcCommitScene(scene->handle);
  throwIfEmbreeError("rtcCommitScene");
  scene_ = std::move(scene);
}

MeshRayCaster::~MeshRayCaster() = default;
MeshRayCaster::MeshRayCaster(MeshRayCaster&&) noexcept = default;
MeshRayCaster& MeshRayCaster::operator=(MeshRayCaster&&) noexcept = default;

RayHit MeshRayCaster::intersect(const Ray& ray) const { return scene_->intersect(ray); }

namespace {

// The Embree ray of a stream entry, reset for a new query.
RTCRay& streamRay(RTCRayHit& entry) {
  entry.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  entry.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return entry.ray;
}
RTCRay& streamRay(RTCRay& entry) { return entry; }

// Feeds `rays` to Embree's ray-stream API with the COHERENT hint, which
// gathers neighbouring rays into SIMD packets that traverse the BVH
// together: 3.4x the rays per second of a loop of single-ray queries for
// camera rays, and no loss for scattered rays (benchmarks/raycast_bench.cc).
// The rays go through a fixed stack buffer, so a batch allocates nothing.
// A ray with an empty segment is left out and reported to `empty(i)`;
// `trace(context, stream, count)` runs the query on a chunk and
// `collect(i, entry)` reads ray i's result.
template <class Entry, class Empty, class Trace, class Collect>
void traceInChunks(std::span<const Ray> rays, const Eigen::Vector3d& offset, Empty empty,
                   Trace trace, Collect collect) {
  constexpr std::size_t kChunk = 256;
  alignas(64) Entry stream[kChunk];
  std::size_t ray_of[kChunk];
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  std::size_t next = 0;
  while (next < rays.size()) {
    std::size_t count = 0;
    for (; next < rays.size() && count < kChunk; ++next) {
      if (!toEmbreeRay(rays[next], offset, &streamRay(stream[count]))) {
        empty(next);
        continue;
      }
      ray_of[count++] = next;
    }
    if (count == 0) continue;
    trace(&context, stream, static_cast<unsigned>(count));
    for (std::size_t k = 0; k < count; ++k) collect(ray_of[k], stream[k]);
  }
}

}  // namespace

void MeshRayCaster::intersect(std::span<const Ray> rays, std::span<RayHit> hits) const {
  if (rays.size() != hits.size()) {
    throw std::invalid_argument("MeshRayCaster::intersect: expected as many hits as rays, got " +
                                std::to_string(hits.size()) + " hits for " +
                                std::to_string(rays.size()) + " rays");
  }
  traceInChunks<RTCRayHit>(
      rays, scene_->offset, [&](std::size_t i) { hits[i] = RayHit{}; },
      [&](RTCIntersectContext* context, RTCRayHit* stream, unsigned count) {
        rtcIntersect1M(scene_->handle, context, stream, count, sizeof(RTCRayHit));
        throwIfEmbreeError("rtcIntersect1M");
      },
      [&](std::size_t i, const RTCRayHit& entry) {
        hits[i] = entry.hit.geomID == RTC_INVALID_GEOMETRY_ID ? RayHit{}
                                                              : scene_->refine(rays[i], entry);
      });
}

bool MeshRayCaster::occluded(const Ray& ray) const {
  alignas(16) RTCRay embree;
  if (!toEmbreeRay(ray, scene_->offset, &embree)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene_->handle, &context, &embree);
  throwIfEmbreeError("rtcOccluded1");
  // Embree marks an occluded ray by setting tfar to -inf.
  return embree.tfar == -std::numeric_limits<float>::infinity();
}

void MeshRayCaster::occluded(std::span<const Ray> rays, std::span<std::uint8_t> occluded) const {
  if (rays.size() != occluded.size()) {
    throw std::invalid_argument(
        "MeshRayCaster::occluded: expected as many results as rays, got " +
        std::to_string(occluded.size()) + " results for " + std::to_string(rays.size()) + " rays");
  }
  // Shadow rays from one image row towards one lamp are coherent enough for
  // the stream's packets to pay off.
  traceInChunks<RTCRay>(
      rays, scene_->offset, [&](std::size_t i) { occluded[i] = 0; },
      [&](RTCIntersectContext* context, RTCRay* stream, unsigned count) {
        rtcOccluded1M(scene_->handle, context, stream, count, sizeof(RTCRay));
        throwIfEmbreeError("rtcOccluded1M");
      },
      [&](std::size_t i, const RTCRay& entry) {
        occluded[i] = entry.tfar == -std::numeric_limits<float>::infinity() ? 1 : 0;
      });
}

Eigen::AlignedBox3d MeshRayCaster::bounds() const { return scene_->bounds; }
const Eigen::Vector3d& MeshRayCaster::sceneOffset() const { return scene_->offset; }
std::size_t MeshRayCaster::triangleCount() const { return scene_->triangles.size(); }
const std::vector<Eigen::Vector3d>& MeshRayCaster::vertices() const { return scene_->vertices; }
const std::vector<Eigen::Vector3i>& MeshRayCaster::triangles() const { return scene_->triangles; }

}  // namespace hsmap
