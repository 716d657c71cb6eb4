// TriangleMeshDistance: distances to the nearest point of a triangle mesh,
// checked against what geometry says for a triangle's face, edge and corner.
#include "pipelines/evaluate/triangle_mesh_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace hsmap {
namespace {

// The triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0.
const std::vector<Eigen::Vector3d> kVertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
const std::vector<Eigen::Vector3i> kTriangle = {{0, 1, 2}};

TEST(TriangleMeshDistanceTest, AboveTheFaceItIsTheHeight) {
  const TriangleMeshDistance mesh(kVertices, kTriangle);
  EXPECT_NEAR(mesh.distance({0.2, 0.3, 0.05}), 0.05, 1e-15);
  EXPECT_NEAR(mesh.distance({0.2, 0.3, -0.7}), 0.7, 1e-15);  // both sides
}

TEST(TriangleMeshDistanceTest, BeyondAnEdgeOrACornerItIsTheDistanceToThem) {
  const TriangleMeshDistance mesh(kVertices, kTriangle);
  // Beyond the hypotenuse x + y = 1, at (0.5, 0.5) + 0.1 * (1, 1) / sqrt(2).
  EXPECT_NEAR(mesh.distance({0.5 + 0.1 / std::sqrt(2.0), 0.5 + 0.1 / std::sqrt(2.0), 0.0}), 0.1,
              1e-12);
  // Beyond the corner (0, 0).
  EXPECT_NEAR(mesh.distance({-0.3, -0.4, 0.0}), 0.5, 1e-12);
}

TEST(TriangleMeshDistanceTest, TheNearestOfSeveralTrianglesCounts) {
  // A second triangle 1 m above the first.
  std::vector<Eigen::Vector3d> vertices = kVertices;
  for (const Eigen::Vector3d& v : kVertices) vertices.push_back(v + Eigen::Vector3d(0, 0, 1));
  const TriangleMeshDistance mesh(vertices, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(mesh.triangleCount(), 2u);
  EXPECT_NEAR(mesh.distance({0.2, 0.2, 0.8}), 0.2, 1e-15);
  const std::vector<double> d = mesh.distances({{0.2, 0.2, 0.1}, {0.2, 0.2, 0.6}, {0.2, 0.2, 2.0}});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_NEAR(d[0], 0.1, 1e-15);
  EXPECT_NEAR(d[1], 0.4, 1e-15);
  EXPECT_NEAR(d[2], 1.0, 1e-15);
}

TEST(TriangleMeshDistanceTest, DegenerateTrianglesAreLeftOut) {
  // A second "triangle" on a line, far away: no area, no distance to it.
  std::vector<Eigen::Vector3d> vertices = kVertices;
  vertices.insert(vertices.end(), {{5, 5, 0}, {6, 6, 0}, {7, 7, 0}});
  const TriangleMeshDistance mesh(vertices, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(mesh.triangleCount(), 1u);
  EXPECT_THROW(TriangleMeshDistance(vertices, {{3, 4, 5}}), std::invalid_argument);
}

TEST(TriangleMeshDistanceTest, BadInputIsRefused) {
  EXPECT_THROW(TriangleMeshDistance(kVertices, {}), std::invalid_argument);
  EXPECT_THROW(TriangleMeshDistance(kVertices, {{0, 1, 3}}), std::invalid_argument);
  std::vector<Eigen::Vector3d> vertices = kVertices;
  vertices[1].x() = NAN;
  EXPECT_THROW(TriangleMeshDistance(vertices, kTriangle), std::invalid_argument);
  const TriangleMeshDistance mesh(kVertices, kTriangle);
  EXPECT_THROW(mesh.distance({NAN, 0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
