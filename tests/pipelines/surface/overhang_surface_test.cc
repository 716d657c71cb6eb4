// A slab sticking out of a vertical wall, seen from beside and below: the
// underside of the overhang is in the surface (not a height field), and the
// space under it is free.
#include <cstdio>

#include <gtest/gtest.h>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

using surface_test::Box;

TEST(OverhangSurface, KeepsTheUndersideOfTheSlab) {
  const Box wall{{-0.5, -2.0, -2.0}, {0.0, 2.0, 2.0}};
  const Box slab{{-0.1, -1.0, 0.5}, {1.5, 1.0, 0.8}};
  std::vector<Eigen::Vector3d> cameras;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) {
      cameras.emplace_back(3.0, -2.0 + i, -1.5 + 1.2 * j);         // beside, facing the wall
      cameras.emplace_back(0.3 + 0.3 * j, -1.0 + 0.5 * i, -1.2);  // below the slab
    }
  const VisibilityPoints points = surface_test::sampleBoxes({wall, slab}, cameras, 250.0, 5);
  ASSERT_GT(points.p_W.size(), 2000u);
  const SurfaceReconstruction result = reconstructSurface(points);
  const SurfaceMesh& mesh = result.mesh;
  const SurfaceCutReport& report = result.report;
  std::printf("overhang: %lld points, %lld cells, %lld rays (%lld cells crossed, %lld steps "
              "through an edge, %lld leaving the hull at their point), %lld triangles, %.3f s (triangulation %.3f, "
              "rays %.3f, cut %.3f, extraction %.3f)\n",
              (long long)report.points, (long long)report.cells, (long long)report.rays,
              (long long)report.cells_crossed, (long long)report.skipped_steps,
              (long long)report.grazing_rays, (long long)report.facets_in_cut,
              report.seconds_total, report.seconds_triangulation, report.seconds_rays,
              report.seconds_cut, report.seconds_extraction);
  EXPECT_EQ(report.rays_cut_short, 0);

  // The underside z = 0.5, x in [0, 1.5], y in [-1, 1]: covered by triangles
  // facing down.
  double underside_area = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d c = surface_test::triangleCentroid(mesh, t);
    const Eigen::Vector3d n = surface_test::triangleNormal(mesh, t);
    if (std::abs(c.z() - 0.5) < 1e-6 && c.x() > 0.0 && n.z() < 0.0)
      underside_area += 0.5 * n.norm();
  }
  EXPECT_GT(underside_area, 0.9 * 1.5 * 2.0);

  // Every triangle lies on the wall or the slab.
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d c = surface_test::triangleCentroid(mesh, t);
    EXPECT_LT(std::min(wall.distanceToSurface(c), slab.distanceToSurface(c)), 0.06)
        << "triangle " << t << " at " << c.transpose();
  }

  // Free under the slab and in front of the wall, matter in the slab and the wall.
  EXPECT_FALSE(result.labelling.isInside({0.75, 0.0, 0.2}));
  EXPECT_FALSE(result.labelling.isInside({0.75, 0.0, -1.0}));
  EXPECT_FALSE(result.labelling.isInside({1.0, 0.5, 0.3}));
  EXPECT_TRUE(result.labelling.isInside({0.75, 0.0, 0.65}));
  EXPECT_TRUE(result.labelling.isInside({1.2, -0.8, 0.7}));
  EXPECT_TRUE(result.labelling.isInside({-0.25, 0.0, -1.0}));
}

}  // namespace
}  // namespace hsmap
