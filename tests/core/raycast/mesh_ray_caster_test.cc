#include "core/raycast/mesh_ray_caster.h"

#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tests/core/raycast/height_field_mesh.h"

namespace hsmap {
namespace {

using test::HeightField;
using test::makeHeightField;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Ray makeRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_near = 0.0,
            double t_far = kInf) {
  Ray ray;
  ray.origin = origin;
  ray.direction = direction.normalized();
  ray.t_near = t_near;
  ray.t_far = t_far;
  return ray;
}

// One triangle in the horizontal plane at depth 40 m (NED: z down).
const std::vector<Eigen::Vector3d> kTriangleVertices = {
    {0.0, 0.0, 40.0}, {1.0, 0.0, 40.0}, {0.0, 1.0, 40.0}};
const std::vector<Eigen::Vector3i> kOneTriangle = {{0, 1, 2}};

// Seabed used by the height-field tests: 40 m deep with 0.3 m undulations.
double seabedDepth(double x, double y) { return 40.0 + 0.3 * std::sin(x) * std::cos(y); }

// |second derivative| of seabedDepth along any unit vector is at most 0.3
// (the Hessian's eigenvalues are -0.3 sin(x +- y)), so linear interpolation
// over a triangle of diameter d = h sqrt(2) is within 0.3 d^2 / 2 = 0.3 h^2.
double interpolationBound(double h) { return 0.3 * h * h; }

// Distance along `ray` to the plane of triangle `index`, computed the
// textbook way (n . (a - o) / n . d), independently of the caster.
double planeDistance(const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<Eigen::Vector3i>& triangles, int index, const Ray& ray) {
  const Eigen::Vector3i& f = triangles[index];
  const Eigen::Vector3d& a = vertices[f[0]];
  const Eigen::Vector3d n = (vertices[f[1]] - a).cross(vertices[f[2]] - a);
  return n.dot(a - ray.origin) / n.dot(ray.direction);
}

bool sameBits(const RayHit& a, const RayHit& b) {
  return std::memcmp(&a.distance, &b.distance, sizeof(double)) == 0 && a.triangle == b.triangle &&
         std::memcmp(&a.u, &b.u, sizeof(double)) == 0 &&
         std::memcmp(&a.v, &b.v, sizeof(double)) == 0 &&
         std::memcmp(a.normal.data(), b.normal.data(), 3 * sizeof(double)) == 0;
}

TEST(MeshRayCaster, SingleTriangleHitFromAboveHasAnalyticDistanceBarycentricsAndNormal) {
  const MeshRayCaster caster(kTriangleVertices, kOneTriangle);
  const RayHit hit = caster.intersect(makeRay({0.2, 0.3, 38.0}, {0.0, 0.0, 1.0}));
  ASSERT_TRUE(hit.hit());
  EXPECT_EQ(hit.triangle, 0);
  EXPECT_NEAR(hit.distance, 2.0, 1e-12);
  EXPECT_NEAR(hit.u, 0.2, 1e-12);
  EXPECT_NEAR(hit.v, 0.3, 1e-12);
  // Facing the origin, which is above the seabed: up is -z in NED.
  EXPECT_NEAR((hit.normal - Eigen::Vector3d(0.0, 0.0, -1.0)).norm(), 0.0, 1e-15);
}

TEST(MeshRayCaster, SingleTriangleHitFromBelowTurnsTheNormalTowardsTheOrigin) {
  const MeshRayCaster caster(kTriangleVertices, kOneTriangle);
  const RayHit hit = caster.intersect(makeRay({0.6, 0.1, 45.0}, {0.0, 0.0, -1.0}));
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.distance, 5.0, 1e-12);
  EXPECT_NEAR(hit.u, 0.6, 1e-12);
  EXPECT_NEAR(hit.v, 0.1, 1e-12);
  EXPECT_NEAR((hit.normal - Eigen::Vector3d(0.0, 0.0, 1.0)).norm(), 0.0, 1e-15);
}

TEST(MeshRayCaster, ReversedWindingGivesTheSameHitAndNormal) {
  // Vertices 2 and 3 swapped: the hit's u and v swap, the normal does not.
  const MeshRayCaster caster(kTriangleVertices, {{0, 2, 1}});
  const RayHit hit = caster.intersect(makeRay({0.2, 0.3, 38.0}, {0.0, 0.0, 1.0}));
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.u, 0.3, 1e-12);
  EXPECT_NEAR(hit.v, 0.2, 1e-12);
  EXPECT_NEAR((hit.normal - Eigen::Vector3d(0.0, 0.0, -1.0)).norm(), 0.0, 1e-15);
}

TEST(MeshRayCaster, ObliqueRayHitsTheTargetPointAtItsDistance) {
  const MeshRayCaster caster(kTriangleVertices, kOneTriangle);
  const Eigen::Vector3d target(0.25, 0.5, 40.0);  // u = 0.25, v = 0.5
  for (const Eigen::Vector3d& direction :
       {Eigen::Vector3d(1.0, 2.0, 2.0), Eigen::Vector3d(-0.3, 0.1, 1.0),
        Eigen::Vector3d(2.0, -1.0, -0.5)}) {
    const Eigen::Vector3d d = direction.normalized();
    const RayHit hit = caster.intersect(makeRay(target - 7.5 * d, d));
    ASSERT_TRUE(hit.hit());
    EXPECT_NEAR(hit.distance, 7.5, 1e-12);
    EXPECT_NEAR(hit.u, 0.25, 1e-12);
    EXPECT_NEAR(hit.v, 0.5, 1e-12);
    EXPECT_LT(hit.normal.dot(d), 0.0);
    EXPECT_NEAR(std::abs(hit.normal.z()), 1.0, 1e-15);
  }
}

TEST(MeshRayCaster, RaysBesideBehindOrParallelToTheTriangleMiss) {
  const MeshRayCaster caster(kTriangleVertices, kOneTriangle);
  // Beside: u + v = 1.2 > 1, in the triangle's plane but outside it.
  EXPECT_FALSE(caster.intersect(makeRay({0.6, 0.6, 38.0}, {0.0, 0.0, 1.0})).hit());
  // Outside the plane's quadrant (u < 0).
  EXPECT_FALSE(caster.intersect(makeRay({-0.1, 0.3, 38.0}, {0.0, 0.0, 1.0})).hit());
  // Pointing away from the triangle.
  EXPECT_FALSE(caster.intersect(makeRay({0.2, 0.3, 38.0}, {0.0, 0.0, -1.0})).hit());
  // Parallel to its plane, 1 m above it.
  EXPECT_FALSE(caster.intersect(makeRay({-1.0, 0.2, 39.0}, {1.0, 0.0, 0.0})).hit());
  const RayHit miss = caster.intersect(makeRay({0.6, 0.6, 38.0}, {0.0, 0.0, 1.0}));
  EXPECT_EQ(miss.triangle, -1);
  EXPECT_EQ(miss.distance, kInf);
}

TEST(MeshRayCaster, SegmentLimitsSelectWhichSurfaceIsHit) {
  // Two parallel triangles, at 40 m (triangle 0) and 42 m (triangle 1).
  std::vector<Eigen::Vector3d> vertices = kTriangleVertices;
  for (const Eigen::Vector3d& p : kTriangleVertices) {
    vertices.push_back(p + Eigen::Vector3d(0.0, 0.0, 2.0));
  }
  const MeshRayCaster caster(vertices, {{0, 1, 2}, {3, 4, 5}});
  const Eigen::Vector3d origin(0.2, 0.3, 38.0), down(0.0, 0.0, 1.0);

  struct Case {
    double t_near, t_far;
    int triangle;  // -1: miss
    double distance;
  };
  const Case cases[] = {
      {0.0, kInf, 0, 2.0},   {0.0, 2.1, 0, 2.0},   {0.0, 1.9, -1, kInf},
      {2.1, kInf, 1, 4.0},   {2.1, 4.1, 1, 4.0},   {2.1, 3.9, -1, kInf},
      {4.1, kInf, -1, kInf}, {3.0, 1.0, -1, kInf},  // t_far < t_near: empty segment
  };
  for (const Case& c : cases) {
    const Ray ray = makeRay(origin, down, c.t_near, c.t_far);
    const RayHit hit = caster.intersect(ray);
    EXPECT_EQ(hit.triangle, c.triangle) << "t_near " << c.t_near << " t_far " << c.t_far;
    if (c.triangle >= 0) {
      EXPECT_NEAR(hit.distance, c.distance, 1e-12);
    } else {
      EXPECT_EQ(hit.distance, kInf);
    }
    EXPECT_EQ(caster.occluded(ray), c.triangle >= 0)
        << "t_near " << c.t_near << " t_far " << c.t_far;
  }
}

// Checks one height-field hit against the analytic surface: the point lies on
// the plane of the hit triangle (distance within 1e-9 m of the independent
// plane distance), inside that triangle (barycentrics reproduce it), the
// triangle is the one under the point, and the point is within the
// interpolation error of the seabed.
void expectOnHeightField(const HeightField& field, const Eigen::Vector3d& offset, const Ray& ray,
                         const RayHit& hit) {
  ASSERT_TRUE(hit.hit());
  const double plane = planeDistance(field.vertices, field.triangles, hit.triangle, ray);
  EXPECT_NEAR(hit.distance, plane, 1e-9);
  const Eigen::Vector3d p = ray.origin + hit.distance * ray.direction;
  const Eigen::Vector3i& f = field.triangles[hit.triangle];
  const Eigen::Vector3d from_barycentrics = (1.0 - hit.u - hit.v) * field.vertices[f[0]] +
                                            hit.u * field.vertices[f[1]] +
                                            hit.v * field.vertices[f[2]];
  EXPECT_LT((p - from_barycentrics).norm(), 1e-9);
  EXPECT_GE(hit.u, 0.0);
  EXPECT_GE(hit.v, 0.0);
  EXPECT_LE(hit.u + hit.v, 1.0);
  const int under = field.triangleUnder(p.x(), p.y(), 1e-6);
  if (under >= 0) {
    EXPECT_EQ(hit.triangle, under);
  }
  const Eigen::Vector3d local = p - offset;
  EXPECT_LE(std::abs(local.z() - seabedDepth(local.x(), local.y())),
            interpolationBound(field.h) + 1e-9);
  EXPECT_NEAR(hit.normal.norm(), 1.0, 1e-12);
  EXPECT_LT(hit.normal.dot(ray.direction), 0.0);
}

// Vertical and oblique rays (up to ~48 degrees off nadir) from 4-12 m above
// the seabed, aimed at random points of a 10 m x 6 m height field whose
// coordinates are shifted by `offset`.
void checkHeightFieldHits(const Eigen::Vector3d& offset) {
  const HeightField field = makeHeightField(
      101, 61, 0.1, offset.x(), offset.y(),
      [&](double x, double y) { return offset.z() + seabedDepth(x - offset.x(), y - offset.y()); });
  const MeshRayCaster caster(field.vertices, field.triangles);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> along_x(0.5, 9.5), along_y(0.5, 5.5);
  std::uniform_real_distribution<double> tilt(-0.8, 0.8), height(4.0, 12.0);
  int checked_under = 0;
  for (int k = 0; k < 400; ++k) {
    const double x = along_x(rng), y = along_y(rng);
    const bool vertical = k % 2 == 0;
    const Eigen::Vector3d d =
        vertical ? Eigen::Vector3d(0, 0, 1) : Eigen::Vector3d(tilt(rng), tilt(rng), 1).normalized();
    // Start `height` metres above the seabed's mean depth, aimed at (x, y).
    const Eigen::Vector3d aim = offset + Eigen::Vector3d(x, y, 40.0);
    const Ray ray = makeRay(aim - height(rng) / d.z() * d, d);
    const RayHit hit = caster.intersect(ray);
    SCOPED_TRACE(k);
    expectOnHeightField(field, offset, ray, hit);
    const Eigen::Vector3d p = ray.origin + hit.distance * ray.direction;
    if (vertical) {
      const Eigen::Vector3d local = p - offset;
      EXPECT_NEAR(local.x(), x, 1e-12);
      EXPECT_NEAR(local.y(), y, 1e-12);
    }
    if (field.triangleUnder(p.x(), p.y(), 1e-6) >= 0) ++checked_under;
  }
  EXPECT_GT(checked_under, 390);  // nearly all hits are away from edges
}

TEST(MeshRayCaster, HeightFieldHitsLieOnTheHitTriangleAndNearTheSurface) {
  checkHeightFieldHits(Eigen::Vector3d::Zero());
}

TEST(MeshRayCaster, MeshFarFromTheOriginKeepsNanometreAccuracy) {
  // 500 m north, 250 m east, 100 m deep: float alone resolves only ~3e-5 m.
  checkHeightFieldHits(Eigen::Vector3d(500.0, 250.0, 60.0));
}

// Random rays over the height field: most hit, some point up or sideways and
// miss, some have short or empty segments.
std::vector<Ray> randomRays(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> x(-1.0, 11.0), y(-1.0, 7.0), z(30.0, 39.0);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (int k = 0; k < count; ++k) {
    Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    if (k % 4 != 0) d.z() = std::abs(d.z()) + 3.0;  // mostly steeply downwards
    Ray ray = makeRay({x(rng), y(rng), z(rng)}, d);
    if (k % 5 == 0) ray.t_far = 15.0 * unit(rng);
    if (k % 7 == 0) ray.t_near = 5.0 * unit(rng);
    rays.push_back(ray);
  }
  return rays;
}

HeightField seabedField() { return makeHeightField(101, 61, 0.1, 0.0, 0.0, seabedDepth); }

TEST(MeshRayCaster, BatchGivesBitIdenticalResultsToSingleRays) {
  const HeightField field = seabedField();
  const MeshRayCaster caster(field.vertices, field.triangles);
  const std::vector<Ray> rays = randomRays(10000, 3);
  std::vector<RayHit> batch(rays.size());
  caster.intersect(rays, batch);
  int hits = 0, misses = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit single = caster.intersect(rays[i]);
    ASSERT_TRUE(sameBits(single, batch[i])) << "ray " << i;
    (single.hit() ? hits : misses)++;
  }
  // Both outcomes are exercised.
  EXPECT_GT(hits, 3000);
  EXPECT_GT(misses, 1000);
}

TEST(MeshRayCaster, ParallelBatchesGiveBitIdenticalResultsToSingleRays) {
  const HeightField field = seabedField();
  const MeshRayCaster caster(field.vertices, field.triangles);
  const std::vector<Ray> rays = randomRays(10000, 4);
  std::vector<RayHit> parallel(rays.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 97),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      caster.intersect(
                          std::span<const Ray>(rays.data() + range.begin(), range.size()),
                          std::span<RayHit>(parallel.data() + range.begin(), range.size()));
                    });
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_TRUE(sameBits(caster.intersect(rays[i]), parallel[i])) << "ray " << i;
  }
}

TEST(MeshRayCaster, OccludedAgreesWithIntersect) {
  const HeightField field = seabedField();
  const MeshRayCaster caster(field.vertices, field.triangles);
  const std::vector<Ray> rays = randomRays(10000, 5);
  int occluded = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const bool expected = caster.intersect(rays[i]).hit();
    ASSERT_EQ(caster.occluded(rays[i]), expected) << "ray " << i;
    occluded += expected;
  }
  EXPECT_GT(occluded, 3000);
  EXPECT_LT(occluded, 9000);
}

TEST(MeshRayCaster, BatchOccludedAgreesWithSingleRays) {
  const HeightField field = seabedField();
  const MeshRayCaster caster(field.vertices, field.triangles);
  // 600 rays: more than two stream chunks, and one with an empty segment.
  std::vector<Ray> rays = randomRays(600, 9);
  rays[300].t_far = rays[300].t_near - 1.0;
  std::vector<std::uint8_t> batch(rays.size(), 7);
  caster.occluded(rays, batch);
  int occluded = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    ASSERT_EQ(batch[i], caster.occluded(rays[i]) ? 1 : 0) << "ray " << i;
    occluded += batch[i];
  }
  EXPECT_EQ(batch[300], 0);
  EXPECT_GT(occluded, 100);
  EXPECT_LT(occluded, 550);
  std::vector<std::uint8_t> too_few(rays.size() - 1);
  EXPECT_THROW(caster.occluded(rays, too_few), std::invalid_argument);
}

TEST(MeshRayCaster, NoRaySlipsThroughSharedEdgesOrCorners) {
  // Vertical rays exactly through grid vertices, cell edges and diagonals
  // (where 2 to 6 triangles meet) must all hit: the traversal is watertight.
  const HeightField field = seabedField();
  const MeshRayCaster caster(field.vertices, field.triangles);
  std::vector<Ray> rays;
  for (int i = 1; i + 1 < field.nx; i += 3) {
    for (int j = 1; j + 1 < field.ny; j += 3) {
      for (const Eigen::Vector2d& fraction :
           {Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(0.0, 0.5),
            Eigen::Vector2d(0.5, 0.5)}) {
        const double x = field.x0 + (i + fraction.x()) * field.h;
        const double y = field.y0 + (j + fraction.y()) * field.h;
        rays.push_back(makeRay({x, y, 30.0}, {0.0, 0.0, 1.0}));
        const RayHit hit = caster.intersect(rays.back());
        ASSERT_TRUE(hit.hit()) << "x " << x << " y " << y;
        expectOnHeightField(field, Eigen::Vector3d::Zero(), rays.back(), hit);
      }
    }
  }
  EXPECT_EQ(rays.size(), 33u * 20u * 4u);
  // Ties between triangles sharing the edge: batch and single rays must
  // still pick the same one.
  std::vector<RayHit> batch(rays.size());
  caster.intersect(rays, batch);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    EXPECT_TRUE(sameBits(caster.intersect(rays[i]), batch[i])) << "ray " << i;
  }
}

TEST(MeshRayCaster, RayThroughASharedEdgeHitsTheLowerIndexedTriangle) {
  // A flat unit square split along its diagonal; the ray crosses the diagonal,
  // where both triangles are hit at the same distance.
  const std::vector<Eigen::Vector3d> square = {
      {0.0, 0.0, 40.0}, {1.0, 0.0, 40.0}, {1.0, 1.0, 40.0}, {0.0, 1.0, 40.0}};
  const Ray ray = makeRay({0.5, 0.5, 38.0}, {0.0, 0.0, 1.0});
  for (const std::vector<Eigen::Vector3i>& triangles :
       {std::vector<Eigen::Vector3i>{{0, 1, 2}, {0, 2, 3}},
        std::vector<Eigen::Vector3i>{{0, 2, 3}, {0, 1, 2}}}) {
    const MeshRayCaster caster(square, triangles);
    const RayHit hit = caster.intersect(ray);
    EXPECT_EQ(hit.triangle, 0);
    EXPECT_NEAR(hit.distance, 2.0, 1e-12);
    std::vector<RayHit> batch(1);
    caster.intersect(std::span<const Ray>(&ray, 1), batch);
    EXPECT_TRUE(sameBits(hit, batch[0]));
  }
}

TEST(MeshRayCaster, ReportsBoundsOfUsedVerticesAndTheMesh) {
  std::vector<Eigen::Vector3d> vertices = kTriangleVertices;
  vertices.emplace_back(100.0, 100.0, 100.0);  // used by no triangle
  const MeshRayCaster caster(vertices, kOneTriangle);
  EXPECT_EQ(caster.triangleCount(), 1u);
  EXPECT_EQ(caster.bounds().min(), Eigen::Vector3d(0.0, 0.0, 40.0));
  EXPECT_EQ(caster.bounds().max(), Eigen::Vector3d(1.0, 1.0, 40.0));
  EXPECT_EQ(caster.sceneOffset(), Eigen::Vector3d(0.5, 0.5, 40.0));
  EXPECT_EQ(caster.vertices(), vertices);
  EXPECT_EQ(caster.triangles(), kOneTriangle);
}

TEST(MeshRayCaster, MovedCasterKeepsWorking) {
  MeshRayCaster first(kTriangleVertices, kOneTriangle);
  MeshRayCaster second(std::move(first));
  EXPECT_NEAR(second.intersect(makeRay({0.2, 0.3, 38.0}, {0, 0, 1})).distance, 2.0, 1e-12);
  MeshRayCaster third(kTriangleVertices, {{0, 2, 1}});
  third = std::move(second);
  EXPECT_NEAR(third.intersect(makeRay({0.2, 0.3, 38.0}, {0, 0, 1})).u, 0.2, 1e-12);
}

template <class F>
void expectInvalidArgument(F&& f, const std::string& message) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument: " << message;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(MeshRayCaster, ConstructorRejectsBadMeshesWithExactMessages) {
  expectInvalidArgument([] { MeshRayCaster(kTriangleVertices, {}); },
                        "MeshRayCaster: expected at least one triangle, got none");
  expectInvalidArgument(
      [] {
        MeshRayCaster(kTriangleVertices, {{0, 1, 2}, {0, 3, 2}});
      },
      "MeshRayCaster: triangle 1 has vertex index 3; expected an index in [0, 3)");
  expectInvalidArgument(
      [] {
        MeshRayCaster(kTriangleVertices, {{0, -1, 2}});
      },
      "MeshRayCaster: triangle 0 has vertex index -1; expected an index in [0, 3)");
  std::vector<Eigen::Vector3d> vertices = kTriangleVertices;
  vertices[2].y() = kNaN;
  expectInvalidArgument([&] { MeshRayCaster(vertices, kOneTriangle); },
                        "MeshRayCaster: vertex 2 has a non-finite coordinate; expected finite "
                        "x, y, z");
  vertices[2].y() = kInf;
  expectInvalidArgument([&] { MeshRayCaster(vertices, kOneTriangle); },
                        "MeshRayCaster: vertex 2 has a non-finite coordinate; expected finite "
                        "x, y, z");
}

TEST(MeshRayCaster, QueriesRejectInvalidRaysAndMismatchedBatches) {
  const MeshRayCaster caster(kTriangleVertices, kOneTriangle);
  Ray ray = makeRay({0.2, 0.3, 38.0}, {0.0, 0.0, 1.0});
  ray.t_near = -1.0;
  const std::string negative_near =
      "MeshRayCaster: expected a ray with a finite origin (within float range of the mesh) and "
      "direction, 0 <= t_near and a t_far that is not NaN; got origin (0.200000, 0.300000, "
      "38.000000), direction (0.000000, 0.000000, 1.000000), t_near -1.000000, t_far inf";
  expectInvalidArgument([&] { caster.intersect(ray); }, negative_near);
  expectInvalidArgument([&] { caster.occluded(ray); }, negative_near);
  ray.t_near = 0.0;
  ray.origin.x() = kNaN;
  EXPECT_THROW(caster.intersect(ray), std::invalid_argument);
  ray.origin.x() = 1e300;  // finite in double, not in float
  EXPECT_THROW(caster.intersect(ray), std::invalid_argument);
  ray.origin.x() = 0.2;
  ray.t_far = kNaN;
  EXPECT_THROW(caster.occluded(ray), std::invalid_argument);

  const std::vector<Ray> rays(3, makeRay({0.2, 0.3, 38.0}, {0.0, 0.0, 1.0}));
  std::vector<RayHit> hits(2);
  expectInvalidArgument([&] { caster.intersect(rays, hits); },
                        "MeshRayCaster::intersect: expected as many hits as rays, got 2 hits for "
                        "3 rays");
}

}  // namespace
}  // namespace hsmap
