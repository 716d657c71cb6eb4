#include "pipelines/simulate/scene/seabed_scene.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "pipelines/simulate/scene/seabed_height_field.h"

namespace hsmap {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d normalOf(const SeabedScene& scene, const Eigen::Vector3i& t) {
  const Eigen::Vector3d& a = scene.vertices[t[0]];
  return (scene.vertices[t[1]] - a).cross(scene.vertices[t[2]] - a);
}

Eigen::Vector3d centroidOf(const SeabedScene& scene, const Eigen::Vector3i& t) {
  return (scene.vertices[t[0]] + scene.vertices[t[1]] + scene.vertices[t[2]]) / 3.0;
}

// Peak-to-peak z of the vertices that belong to seabed triangles.
double seabedPeakToPeak(const SeabedScene& scene) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::seabed) continue;
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, scene.vertices[scene.triangles[i][k]].z());
      hi = std::max(hi, scene.vertices[scene.triangles[i][k]].z());
    }
  }
  return hi - lo;
}

std::size_t countKind(const SeabedScene& scene, SurfaceKind kind) {
  return std::count(scene.triangle_kind.begin(), scene.triangle_kind.end(), kind);
}

// The default scene (rugged, 26 m x 6 m at 2 cm, seed 1), built once.
class DefaultRuggedScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = std::make_unique<SeabedScene>(buildSeabedScene(SeabedSceneConfig()));
    field_ = std::make_unique<SeabedHeightField>(SeabedSceneConfig());
  }
  static void TearDownTestSuite() {
    scene_.reset();
    field_.reset();
  }
  static std::unique_ptr<SeabedScene> scene_;
  static std::unique_ptr<SeabedHeightField> field_;
};
std::unique_ptr<SeabedScene> DefaultRuggedScene::scene_;
std::unique_ptr<SeabedHeightField> DefaultRuggedScene::field_;

TEST_F(DefaultRuggedScene, IsAWellFormedTriangleSoupOfTheAdvertisedSize) {
  const SeabedScene& scene = *scene_;
  ASSERT_EQ(scene.triangle_kind.size(), scene.triangles.size());
  // 1301 x 301 grid vertices, 2 x 1300 x 300 grid triangles, then the rocks.
  EXPECT_GE(scene.triangles.size(), 780000u + 50000u);
  EXPECT_LE(scene.triangles.size(), 1100000u);
  const int vertex_count = static_cast<int>(scene.vertices.size());
  double smallest_area = std::numeric_limits<double>::infinity();
  for (const auto& t : scene.triangles) {
    ASSERT_TRUE(t.minCoeff() >= 0 && t.maxCoeff() < vertex_count) << t.transpose();
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) << t.transpose();
    smallest_area = std::min(smallest_area, 0.5 * normalOf(scene, t).norm());
  }
  // The smallest rock facets are a few mm across (1e-5 m^2); nothing is degenerate.
  EXPECT_GT(smallest_area, 1e-6);
  for (const auto& v : scene.vertices) ASSERT_TRUE(v.allFinite());
}

TEST_F(DefaultRuggedScene, GridCoversTheExtentExactlyFacesUpAndSamplesTheHeightField) {
  const SeabedScene& scene = *scene_;
  const SeabedSceneConfig config;
  double north_lo = 1e9, north_hi = -1e9, east_lo = 1e9, east_hi = -1e9;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::seabed) continue;
    const Eigen::Vector3i& t = scene.triangles[i];
    ASSERT_LT(normalOf(scene, t).z(), 0.0) << "seabed triangle " << i << " faces down";
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = scene.vertices[t[k]];
      north_lo = std::min(north_lo, v.x());
      north_hi = std::max(north_hi, v.x());
      east_lo = std::min(east_lo, v.y());
      east_hi = std::max(east_hi, v.y());
      ASSERT_EQ(v.z(), field_->z(v.x(), v.y()));
    }
  }
  EXPECT_EQ(north_lo, config.north_min_m);
  EXPECT_EQ(north_hi, config.north_max_m);
  EXPECT_EQ(east_lo, config.east_min_m);
  EXPECT_EQ(east_hi, config.east_max_m);
  // The rocks stay inside the extent too.
  for (const auto& v : scene.vertices) {
    ASSERT_GE(v.x(), config.north_min_m);
    ASSERT_LE(v.x(), config.north_max_m);
    ASSERT_GE(v.y(), config.east_min_m);
    ASSERT_LE(v.y(), config.east_max_m);
  }
  // Grid spacing is the configured cell.
  EXPECT_NEAR(scene.vertices[1].y() - scene.vertices[0].y(), config.cell_m, 1e-12);
}

TEST_F(DefaultRuggedScene, RocksAreClosedAndConsistentlyWound) {
  const SeabedScene& scene = *scene_;
  std::map<std::pair<int, int>, int> edges;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::rock) continue;
    const Eigen::Vector3i& t = scene.triangles[i];
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  ASSERT_FALSE(edges.empty());
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << edge.first << "-" << edge.second;
    ASSERT_TRUE(edges.count({edge.second, edge.first})) << "open edge " << edge.first;
  }
}

TEST_F(DefaultRuggedScene, HasAnOverhangAHeightFieldCannotHold) {
  const SeabedScene& scene = *scene_;
  int overhanging = 0;
  double highest_underside = 0.0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::rock) continue;
    const Eigen::Vector3d normal = normalOf(scene, scene.triangles[i]).normalized();
    const Eigen::Vector3d centroid = centroidOf(scene, scene.triangles[i]);
    // NED: z > 0.5 faces down; height above the seabed is z_seabed - z.
    const double height = field_->z(centroid.x(), centroid.y()) - centroid.z();
    if (normal.z() > 0.5 && height >= 0.1) {
      ++overhanging;
      highest_underside = std::max(highest_underside, height);
    }
  }
  EXPECT_GT(overhanging, 100);
  EXPECT_GT(highest_underside, 0.25);
}

TEST_F(DefaultRuggedScene, HasSteepSlopesButNoCliffs) {
  const SeabedScene& scene = *scene_;
  double steepest_deg = 0.0;
  std::size_t steeper_than_45 = 0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::seabed) continue;
    // The angle between the facet's normal and the vertical (up is -z).
    const Eigen::Vector3d normal = normalOf(scene, scene.triangles[i]).normalized();
    const double slope_deg = std::acos(std::clamp(-normal.z(), -1.0, 1.0)) * 180.0 / kPi;
    steepest_deg = std::max(steepest_deg, slope_deg);
    steeper_than_45 += slope_deg > 45.0;
  }
  EXPECT_GT(steepest_deg, 55.0);
  EXPECT_LT(steepest_deg, 80.0);
  // The scarp face and the ridge flanks: several square metres, not a few facets.
  EXPECT_GT(steeper_than_45 * 0.5 * 0.02 * 0.02, 2.0);
}

TEST_F(DefaultRuggedScene, CorridorHoldsRocksAlongTheWholeTrack) {
  const SeabedScene& scene = *scene_;
  const SeabedSceneConfig config;
  // Rock facets with |east| <= 1 m in every 3 m of north.
  constexpr double kWindowM = 3.0;
  const int windows = static_cast<int>((config.north_max_m - config.north_min_m) / kWindowM);
  std::vector<int> hits(windows, 0);
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::rock) continue;
    const Eigen::Vector3d c = centroidOf(scene, scene.triangles[i]);
    const int w = static_cast<int>((c.x() - config.north_min_m) / kWindowM);
    if (std::abs(c.y()) <= 1.0 && w >= 0 && w < windows) ++hits[w];
  }
  for (int w = 0; w < windows; ++w) EXPECT_GT(hits[w], 0) << "north window " << w;
}

TEST_F(DefaultRuggedScene, VehicleCanFlyOverEveryRock) {
  const SeabedScene& scene = *scene_;
  double highest = 0.0;
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    if (scene.triangle_kind[i] != SurfaceKind::rock) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = scene.vertices[scene.triangles[i][k]];
      highest = std::max(highest, field_->z(v.x(), v.y()) - v.z());
    }
  }
  EXPECT_GT(highest, 0.4);  // the perched boulder and the slab stand out
  EXPECT_LT(highest, 1.0);
}

TEST(SeabedScene, ReliefMatchesEachPreset) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SeabedSceneConfig config;
    config.seed = seed;
    config.cell_m = seed == 1 ? 0.02 : 0.05;  // the default grid once, coarser ones for speed
    config.terrain = TerrainPreset::flat;
    const SeabedScene flat = buildSeabedScene(config);
    EXPECT_LT(seabedPeakToPeak(flat), 0.05) << "seed " << seed;
    EXPECT_GT(seabedPeakToPeak(flat), 0.003) << "seed " << seed;  // rough, not a plane
    EXPECT_EQ(countKind(flat, SurfaceKind::rock), 0u);
    config.terrain = TerrainPreset::low_relief;
    const SeabedScene low = buildSeabedScene(config);
    EXPECT_GT(seabedPeakToPeak(low), 0.1) << "seed " << seed;
    EXPECT_LT(seabedPeakToPeak(low), 0.5) << "seed " << seed;
    EXPECT_EQ(countKind(low, SurfaceKind::rock), 0u);
    config.terrain = TerrainPreset::rugged;
    const SeabedScene rugged = buildSeabedScene(config);
    EXPECT_GE(seabedPeakToPeak(rugged), 1.0) << "seed " << seed;
    EXPECT_GT(countKind(rugged, SurfaceKind::rock), 20000u) << "seed " << seed;
  }
}

TEST(SeabedScene, MeanDepthIsTheConfiguredOne) {
  SeabedSceneConfig config;
  config.terrain = TerrainPreset::low_relief;
  config.seabed_depth_m = 12.5;
  const SeabedScene scene = buildSeabedScene(config);
  double sum = 0.0;
  for (const auto& v : scene.vertices) sum += v.z();
  EXPECT_NEAR(sum / scene.vertices.size(), 12.5, 0.1);
}

TEST(SeabedScene, SameSeedSameSceneOtherSeedOtherScene) {
  SeabedSceneConfig config;
  config.north_min_m = 0.0;
  config.north_max_m = 8.0;
  config.east_min_m = -2.0;
  config.east_max_m = 2.0;
  config.seed = 7;
  const SeabedScene a = buildSeabedScene(config);
  const SeabedScene b = buildSeabedScene(config);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_kind, b.triangle_kind);
  config.seed = 8;
  const SeabedScene c = buildSeabedScene(config);
  ASSERT_GE(c.vertices.size(), 401u * 201u);
  int differing = 0;
  for (std::size_t i = 0; i < 401u * 201u; ++i) differing += a.vertices[i] != c.vertices[i];
  EXPECT_GT(differing, 401 * 201 * 9 / 10);
}

TEST(SeabedScene, ExtentThatIsNotAMultipleOfTheCellIsStillCoveredExactly) {
  SeabedSceneConfig config;
  config.terrain = TerrainPreset::flat;
  config.north_min_m = 1.0;
  config.north_max_m = 2.01;
  config.east_min_m = -0.5;
  config.east_max_m = 0.5;
  config.cell_m = 0.1;
  const SeabedScene scene = buildSeabedScene(config);
  // ceil(1.01 / 0.1) = 11 rows of cells, 10 columns.
  EXPECT_EQ(scene.vertices.size(), 12u * 11u);
  EXPECT_EQ(scene.triangles.size(), 2u * 11u * 10u);
  EXPECT_EQ(scene.vertices.front().x(), 1.0);
  EXPECT_EQ(scene.vertices.back().x(), 2.01);
  EXPECT_EQ(scene.vertices.front().y(), -0.5);
  EXPECT_EQ(scene.vertices.back().y(), 0.5);
}

void expectRejected(const SeabedSceneConfig& config, const char* message) {
  try {
    buildSeabedScene(config);
    ADD_FAILURE() << "expected std::invalid_argument: " << message;
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), message);
  }
}

// A slope adds a plane to the height field: every grid vertex moves by it
// exactly, and each rock by the plane somewhere under it (rocks rest on the
// deepest seabed point below them), so within tan(slope) x 1.5 m of the plane
// at its own place.
TEST(SeabedScene, SlopeTiltsTheSeabedAndTheRocksMoveWithIt) {
  SeabedSceneConfig config;
  config.north_min_m = -3.0;
  config.north_max_m = 9.0;
  config.cell_m = 0.05;
  const SeabedScene level = buildSeabedScene(config);
  config.slope_deg = 20.0;
  config.slope_direction_deg = 30.0;  // downhill north-north-east
  const SeabedScene sloped = buildSeabedScene(config);
  ASSERT_EQ(level.vertices.size(), sloped.vertices.size());
  ASSERT_EQ(level.triangles, sloped.triangles);
  const double gradient = std::tan(20.0 * kPi / 180.0);
  const Eigen::Vector2d downhill(std::cos(30.0 * kPi / 180.0), std::sin(30.0 * kPi / 180.0));
  auto plane = [&](const Eigen::Vector3d& p) { return gradient * downhill.dot(p.head<2>()); };
  std::size_t grid_vertices = 0;
  while (grid_vertices < level.vertices.size() &&
         std::abs(sloped.vertices[grid_vertices].z() - level.vertices[grid_vertices].z() -
                  plane(level.vertices[grid_vertices])) < 1e-9) {
    ++grid_vertices;
  }
  // The grid is listed first: (12 / 0.05 + 1) x (6 / 0.05 + 1) vertices.
  EXPECT_EQ(grid_vertices, std::size_t(241 * 121));
  ASSERT_LT(grid_vertices, level.vertices.size());  // rugged: rocks follow
  for (std::size_t i = grid_vertices; i < level.vertices.size(); ++i) {
    // Rocks stay where they were drawn; only the leaning slab, whose tilt
    // follows the seabed between its foot and its support, shifts a little.
    EXPECT_LT((sloped.vertices[i] - level.vertices[i]).head<2>().norm(), 0.3) << "vertex " << i;
    EXPECT_NEAR(sloped.vertices[i].z() - level.vertices[i].z(), plane(level.vertices[i]),
                gradient * 1.5)
        << "vertex " << i;
  }
}

// A heading turns the finished scene about the pivot: the same vertices,
// rotated clockwise, same triangles.
TEST(SeabedScene, HeadingTurnsTheSceneAboutThePivot) {
  SeabedSceneConfig config;
  config.north_min_m = -3.0;
  config.north_max_m = 6.0;
  config.cell_m = 0.05;
  const SeabedScene north = buildSeabedScene(config);
  config.heading_deg = -70.0;
  config.pivot_north_m = 1.0;
  config.pivot_east_m = -0.5;
  const SeabedScene turned = buildSeabedScene(config);
  ASSERT_EQ(north.vertices.size(), turned.vertices.size());
  ASSERT_EQ(north.triangles, turned.triangles);
  const double h = -70.0 * kPi / 180.0;
  for (std::size_t i = 0; i < north.vertices.size(); i += 7) {
    const Eigen::Vector3d& p = north.vertices[i];
    const double dn = p.x() - 1.0, de = p.y() + 0.5;
    EXPECT_NEAR(turned.vertices[i].x(), 1.0 + std::cos(h) * dn - std::sin(h) * de, 1e-9);
    EXPECT_NEAR(turned.vertices[i].y(), -0.5 + std::sin(h) * dn + std::cos(h) * de, 1e-9);
    EXPECT_EQ(turned.vertices[i].z(), p.z());
  }
}

TEST(SeabedScene, RejectsInvalidConfigsSayingWhatWasExpected) {
  SeabedSceneConfig config;
  config.north_max_m = -3.0;
  expectRejected(config,
                 "SeabedSceneConfig: north_max_m must be greater than north_min_m, got -3 .. -3");
  config = SeabedSceneConfig();
  config.east_min_m = 4.0;
  expectRejected(config,
                 "SeabedSceneConfig: east_max_m must be greater than east_min_m, got 4 .. 3");
  config = SeabedSceneConfig();
  config.cell_m = 0.0;
  expectRejected(config, "SeabedSceneConfig: cell_m must be positive, got 0");
  config.cell_m = 7.0;
  expectRejected(config,
                 "SeabedSceneConfig: cell_m must not exceed the extent (26 m x 6 m), got 7");
  config.cell_m = 0.0005;
  expectRejected(config,
                 "SeabedSceneConfig: cell_m 0.0005 gives 6.24064e+08 grid vertices, at most 4e+07 "
                 "are allowed");
  config = SeabedSceneConfig();
  config.seabed_depth_m = std::nan("");
  expectRejected(config, "SeabedSceneConfig: seabed_depth_m must be finite, got nan");
  config = SeabedSceneConfig();
  config.east_max_m = std::numeric_limits<double>::infinity();
  expectRejected(config, "SeabedSceneConfig: east_max_m must be finite, got inf");
  // The height field validates the same way.
  EXPECT_THROW(SeabedHeightField{config}, std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
