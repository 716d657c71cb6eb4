#include "core/raycast/triangle_plane_hit.h"

#include <gtest/gtest.h>

#include <random>

namespace hsmap {
namespace {

TEST(TrianglePlaneHit, RecoversDistanceAndBarycentricsOfAKnownPoint) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0), weight(-0.5, 1.5);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d b(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d c(coordinate(rng), coordinate(rng), coordinate(rng));
    // Points outside the triangle too: the plane, not the triangle, is hit.
    const double u = weight(rng), v = weight(rng);
    const Eigen::Vector3d target = (1.0 - u - v) * a + u * b + v * c;
    const Eigen::Vector3d d =
        Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)).normalized();
    const double t = coordinate(rng);  // negative: plane behind the origin
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    if (std::abs(normal.dot(d)) < 0.1) continue;  // keep the problem well conditioned
    TrianglePlaneHit hit;
    ASSERT_TRUE(intersectTrianglePlane(target - t * d, d, a, b, c, &hit));
    EXPECT_NEAR(hit.t, t, 1e-12);
    EXPECT_NEAR(hit.u, u, 1e-11);
    EXPECT_NEAR(hit.v, v, 1e-11);
  }
}

TEST(TrianglePlaneHit, RemainsAccurateFarFromTheOrigin) {
  // A 2 cm triangle 500 m north and 100 m deep, seen from 2 m above.
  const Eigen::Vector3d a(500.0, 250.0, 100.0), b(500.02, 250.0, 100.001), c(500.0, 250.02, 99.999);
  const Eigen::Vector3d target = 0.5 * a + 0.2 * b + 0.3 * c;
  const Eigen::Vector3d d = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  TrianglePlaneHit hit;
  ASSERT_TRUE(intersectTrianglePlane(target - 2.0 * d, d, a, b, c, &hit));
  EXPECT_NEAR(hit.t, 2.0, 1e-12);
  EXPECT_NEAR(hit.u, 0.2, 1e-10);
  EXPECT_NEAR(hit.v, 0.3, 1e-10);
}

TEST(TrianglePlaneHit, ParallelRayAndDegenerateTriangleReportNoHit) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  TrianglePlaneHit hit{7.0, 8.0, 9.0};
  EXPECT_FALSE(intersectTrianglePlane({0, 0, 1}, {1, 0, 0}, a, b, c, &hit));
  EXPECT_FALSE(intersectTrianglePlane({0, 0, 1}, {0, 0, 1}, a, b, 2.0 * b, &hit));
  EXPECT_FALSE(intersectTrianglePlane({0, 0, 1}, {0, 0, 1}, a, a, a, &hit));
  // Untouched on failure.
  EXPECT_EQ(hit.t, 7.0);
  EXPECT_EQ(hit.u, 8.0);
  EXPECT_EQ(hit.v, 9.0);
}

}  // namespace
}  // namespace hsmap
