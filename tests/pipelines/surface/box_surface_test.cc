// The surface of a box seen from cameras all around it: closed, on the box,
// outward, with the box's inside labelled matter and its outside free.
#include <chrono>
#include <cstdio>

#include <gtest/gtest.h>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

using surface_test::Box;

TEST(BoxSurface, IsClosedOutwardAndOnTheBox) {
  const Box box{{-1.0, -0.7, -0.5}, {1.0, 0.7, 0.5}};
  const VisibilityPoints points = surface_test::sampleBoxes(
      {box}, surface_test::camerasAround(Eigen::Vector3d::Zero(), 4.0, 40), 400.0, 7);
  ASSERT_GT(points.p_W.size(), 2000u);
  const SurfaceReconstruction result = reconstructSurface(points);
  const SurfaceMesh& mesh = result.mesh;
  std::printf("box: %lld points, %lld cells, %lld rays, %lld triangles, %lld skipped steps, %.3f s "
              "(triangulation %.3f, rays %.3f, cut %.3f)\n",
              (long long)result.report.points, (long long)result.report.cells,
              (long long)result.report.rays, (long long)result.report.facets_in_cut,
              (long long)result.report.skipped_steps, result.report.seconds_total,
              result.report.seconds_triangulation, result.report.seconds_rays,
              result.report.seconds_cut);
  EXPECT_EQ(result.report.rays_cut_short, 0);
  ASSERT_FALSE(mesh.triangles.empty());

  // Every vertex is an input point and every triangle lies on the box (a
  // triangle across a box edge dips inside by a fraction of the spacing).
  EXPECT_EQ(mesh.vertices.size(), mesh.point_index.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    EXPECT_LT(box.distanceToSurface(mesh.vertices[i]), 1e-12);
    EXPECT_EQ(mesh.vertices[i], points.p_W[mesh.point_index[i]]);
  }
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    EXPECT_LT(box.distanceToSurface(surface_test::triangleCentroid(mesh, t)), 0.05) << "triangle " << t;

  // Closed and outward: no open edge, area and enclosed volume the box's.
  EXPECT_EQ(surface_test::openEdges(mesh), 0);
  const Eigen::Vector3d size = box.hi - box.lo;
  const double box_area = 2.0 * (size.x() * size.y() + size.y() * size.z() + size.z() * size.x());
  EXPECT_NEAR(surface_test::area(mesh), box_area, 0.03 * box_area);
  EXPECT_NEAR(surface_test::signedVolume(mesh), size.prod(), 0.05 * size.prod());
  EXPECT_EQ(surface_test::componentSizes(mesh).size(), 1u);

  // Inside is matter, outside free space.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.8, 0.5, 0.3),
                                   Eigen::Vector3d(-0.9, -0.6, -0.4)})
    EXPECT_TRUE(result.labelling.isInside(x)) << x.transpose();
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(1.3, 0, 0), Eigen::Vector3d(0, 0, 0.8),
                                   Eigen::Vector3d(0, -1.2, 0), Eigen::Vector3d(3, 3, 3),
                                   Eigen::Vector3d(0, 0, -10)})
    EXPECT_FALSE(result.labelling.isInside(x)) << x.transpose();
}

TEST(BoxSurface, RejectsInvalidPoints) {
  VisibilityPoints points;
  points.p_W = {Eigen::Vector3d(0, 0, 0)};
  points.views = {{3}};
  points.c_W = {Eigen::Vector3d(1, 1, 1)};
  EXPECT_THROW(reconstructSurface(points), std::invalid_argument);
}

TEST(BoxSurface, RejectsFlatPoints) {
  VisibilityPoints points;
  for (int i = 0; i < 10; ++i) {
    points.p_W.emplace_back(i % 3, i / 3, 0.0);
    points.views.push_back({0});
  }
  points.c_W = {Eigen::Vector3d(0, 0, 5)};
  EXPECT_THROW(reconstructSurface(points), std::runtime_error);
}

}  // namespace
}  // namespace hsmap
