#include "pipelines/simulate/scene/rock_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Closed and consistently wound: every directed edge (a, b) occurs exactly
// once and its reverse (b, a) exactly once.
void expectClosedAndConsistentlyWound(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
    const auto reverse = edges.find({edge.second, edge.first});
    ASSERT_NE(reverse, edges.end()) << "open edge " << edge.first << "-" << edge.second;
  }
}

// Signed volume by the divergence theorem: positive for outward normals.
double signedVolume(const TriangleMesh& mesh, const Eigen::Vector3d& centre) {
  double volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - centre, b = mesh.vertices[t[1]] - centre,
                          c = mesh.vertices[t[2]] - centre;
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

TEST(RockMesh, IcosphereHasTheExpectedCountsAndIsClosed) {
  for (int s = 0; s <= 4; ++s) {
    const TriangleMesh sphere = makeIcosphere(s);
    const int four_s = 1 << (2 * s);
    EXPECT_EQ(sphere.vertices.size(), static_cast<std::size_t>(10 * four_s + 2));
    EXPECT_EQ(sphere.triangles.size(), static_cast<std::size_t>(20 * four_s));
    for (const auto& v : sphere.vertices) EXPECT_NEAR(v.norm(), 1.0, 1e-12);
    expectClosedAndConsistentlyWound(sphere);
  }
}

TEST(RockMesh, IcosphereNormalsPointOutwardAndVolumeApproachesTheBall) {
  const TriangleMesh sphere = makeIcosphere(4);
  for (const auto& t : sphere.triangles) {
    const Eigen::Vector3d& a = sphere.vertices[t[0]];
    const Eigen::Vector3d normal = (sphere.vertices[t[1]] - a).cross(sphere.vertices[t[2]] - a);
    ASSERT_GT(normal.dot(a + sphere.vertices[t[1]] + sphere.vertices[t[2]]), 0.0);
  }
  // An inscribed polyhedron of 5120 faces holds 99% of the ball's volume.
  EXPECT_NEAR(signedVolume(sphere, Eigen::Vector3d::Zero()), 4.0 / 3.0 * kPi,
              0.01 * 4.0 / 3.0 * kPi);
}

TEST(RockMesh, RockIsAClosedOutwardStarShapedSurfaceOfTheRightSize) {
  const TriangleMesh sphere = makeIcosphere(3);
  RockShape shape;
  shape.semi_axes_m = Eigen::Vector3d(0.4, 0.3, 0.2);
  shape.roughness = 0.3;
  shape.planar_cuts = 5;
  shape.q_W_R = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  shape.seed = 17;
  const TriangleMesh rock = makeRockMesh(shape, sphere);
  ASSERT_EQ(rock.vertices.size(), sphere.vertices.size());
  EXPECT_EQ(rock.triangles, sphere.triangles);
  expectClosedAndConsistentlyWound(rock);
  // Star-shaped around the centre: every vertex lies along its sphere
  // direction (rotated and scaled by the semi-axes) at a positive distance,
  // between 20% and 130% of the ellipsoid radius in that direction.
  const Eigen::Matrix3d R_W_R = shape.q_W_R.toRotationMatrix();
  for (std::size_t i = 0; i < rock.vertices.size(); ++i) {
    const Eigen::Vector3d v_R = R_W_R.transpose() * rock.vertices[i];
    const Eigen::Vector3d on_ellipsoid = shape.semi_axes_m.cwiseProduct(sphere.vertices[i]);
    const double ratio = v_R.norm() / on_ellipsoid.norm();
    EXPECT_NEAR(v_R.normalized().dot(on_ellipsoid.normalized()), 1.0, 1e-12);
    EXPECT_GT(ratio, 0.2);
    EXPECT_LT(ratio, 1.3);
  }
  const double ellipsoid = 4.0 / 3.0 * kPi * 0.4 * 0.3 * 0.2;
  const double volume = signedVolume(rock, Eigen::Vector3d::Zero());
  EXPECT_GT(volume, 0.3 * ellipsoid);
  EXPECT_LT(volume, 1.3 * ellipsoid);
}

TEST(RockMesh, SameSeedSameRockOtherSeedOtherRock) {
  const TriangleMesh sphere = makeIcosphere(2);
  RockShape shape;
  shape.seed = 3;
  const TriangleMesh a = makeRockMesh(shape, sphere), b = makeRockMesh(shape, sphere);
  EXPECT_EQ(a.vertices, b.vertices);
  shape.seed = 4;
  const TriangleMesh c = makeRockMesh(shape, sphere);
  double largest_difference = 0.0;
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    largest_difference = std::max(largest_difference, (a.vertices[i] - c.vertices[i]).norm());
  }
  EXPECT_GT(largest_difference, 0.02);
}

TEST(RockMesh, PlanarCutsMakeFlatFaces) {
  // One cut: the vertices on the cut plane are coplanar, so many triangles
  // share exactly the same normal direction.
  const TriangleMesh sphere = makeIcosphere(3);
  RockShape shape;
  shape.semi_axes_m = Eigen::Vector3d(0.3, 0.3, 0.3);
  shape.roughness = 0.0;
  shape.planar_cuts = 1;
  shape.seed = 5;
  const TriangleMesh rock = makeRockMesh(shape, sphere);
  // Without roughness the only other displacement is the 3% fine noise, so
  // count faces whose normal is within 3 degrees of the most common one.
  std::vector<Eigen::Vector3d> normals;
  for (const auto& t : rock.triangles) {
    const Eigen::Vector3d& a = rock.vertices[t[0]];
    normals.push_back((rock.vertices[t[1]] - a).cross(rock.vertices[t[2]] - a).normalized());
  }
  int best = 0;
  for (const auto& n : normals) {
    int aligned = 0;
    for (const auto& m : normals) aligned += n.dot(m) > std::cos(3.0 * kPi / 180.0);
    best = std::max(best, aligned);
  }
  EXPECT_GE(best, 20);
}

TEST(RockMesh, RejectsBadArguments) {
  try {
    makeIcosphere(8);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "makeIcosphere: subdivisions must be in [0, 7], got 8");
  }
  EXPECT_THROW(makeIcosphere(-1), std::invalid_argument);
  const TriangleMesh sphere = makeIcosphere(1);
  RockShape shape;
  shape.semi_axes_m.y() = 0.0;
  try {
    makeRockMesh(shape, sphere);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "makeRockMesh: semi_axes_m must be positive and finite");
  }
  shape = RockShape();
  shape.roughness = 0.95;
  try {
    makeRockMesh(shape, sphere);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "makeRockMesh: roughness must be in [0, 0.9], got 0.95");
  }
  shape = RockShape();
  shape.planar_cuts = -1;
  EXPECT_THROW(makeRockMesh(shape, sphere), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
