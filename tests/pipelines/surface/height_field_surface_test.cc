// A plane with a bump, seen from cameras above it (a seabed): one sheet
// over the middle, on the field, facing the cameras; matter below.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

double bump(double x, double y) { return 0.4 * std::exp(-(x * x + y * y) / (2.0 * 0.3 * 0.3)); }

std::vector<Eigen::Vector3d> camerasAbove(double half, double height, int per_side) {
  std::vector<Eigen::Vector3d> cameras;
  for (int i = 0; i < per_side; ++i)
    for (int j = 0; j < per_side; ++j)
      cameras.emplace_back(-half + 2.0 * half * i / (per_side - 1),
                           -half + 2.0 * half * j / (per_side - 1), height);
  return cameras;
}

TEST(HeightFieldSurface, IsOneSheetOnTheFieldFacingTheCameras) {
  const double noise = 0.002;
  const VisibilityPoints points = surface_test::sampleHeightField(
      bump, 2.0, 5000, noise, camerasAbove(2.0, 2.5, 6), 11);
  ASSERT_GT(points.p_W.size(), 4500u);
  const SurfaceReconstruction result = reconstructSurface(points);
  const SurfaceMesh& mesh = result.mesh;
  std::printf("height field: %lld points, %lld cells, %lld rays, %lld triangles, %.3f s\n",
              (long long)result.report.points, (long long)result.report.cells,
              (long long)result.report.rays, (long long)result.report.facets_in_cut,
              result.report.seconds_total);
  ASSERT_FALSE(mesh.triangles.empty());

  // Over the middle: on the field (within the noise and the chord of the
  // bump's curvature) and facing up. A handful of tiny folds remain where
  // the noise makes flat slivers in the surface layer (10 triangles of
  // about 5600, each under 0.004 m^2, when this was written).
  int middle = 0, facing_up = 0;
  double middle_area = 0.0, facing_down_area = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d centroid = surface_test::triangleCentroid(mesh, t);
    if (std::abs(centroid.x()) > 1.5 || std::abs(centroid.y()) > 1.5) continue;
    ++middle;
    EXPECT_NEAR(centroid.z(), bump(centroid.x(), centroid.y()), 0.02) << "triangle " << t;
    const Eigen::Vector3d normal = surface_test::triangleNormal(mesh, t);
    middle_area += 0.5 * normal.norm();
    if (normal.z() > 0.0)
      ++facing_up;
    else
      facing_down_area += 0.5 * normal.norm();
  }
  EXPECT_GT(middle, 3000);
  EXPECT_GE(facing_up, 0.995 * middle);
  EXPECT_LT(facing_down_area, 0.002 * middle_area);
  // The field's area over the middle (the bump adds about 0.1 m^2 to 9).
  EXPECT_NEAR(middle_area, 9.1, 0.3);

  // One sheet: every vertical line through the middle crosses one triangle.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  int single = 0;
  for (int s = 0; s < 200; ++s) single += surface_test::sheetsAbove(mesh, coordinate(rng), coordinate(rng)) == 1;
  EXPECT_GE(single, 198);

  // Matter below the field, free space above.
  EXPECT_TRUE(result.labelling.isInside({0.0, 0.0, 0.2}));
  EXPECT_TRUE(result.labelling.isInside({1.0, -0.5, -0.3}));
  EXPECT_FALSE(result.labelling.isInside({0.0, 0.0, 0.6}));
  EXPECT_FALSE(result.labelling.isInside({1.0, 1.0, 0.3}));
}

}  // namespace
}  // namespace hsmap
