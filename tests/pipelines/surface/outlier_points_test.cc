// A few points floating in free space, each seen by some cameras, next to a
// box: the rays to the box carve them away, so they make no surface blobs.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

using surface_test::Box;

TEST(OutlierPoints, MakeNoSurfaceBlobs) {
  const Box box{{-1.0, -0.7, -0.5}, {1.0, 0.7, 0.5}};
  VisibilityPoints points = surface_test::sampleBoxes(
      {box}, surface_test::camerasAround(Eigen::Vector3d::Zero(), 4.0, 40), 300.0, 13);
  const std::size_t first_outlier = points.p_W.size();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  while (points.p_W.size() < first_outlier + 15) {
    const Eigen::Vector3d p(coordinate(rng), coordinate(rng), coordinate(rng));
    if (box.distanceToSurface(p) < 0.3 || box.containsStrictly(p, 0.0)) continue;
    // Seen by the three cameras nearest it whose sight line misses the box.
    std::vector<std::pair<double, int>> by_distance;
    for (std::size_t k = 0; k < points.c_W.size(); ++k)
      if (!surface_test::segmentHitsBox(p, points.c_W[k], box, 0.0))
        by_distance.emplace_back((points.c_W[k] - p).norm(), static_cast<int>(k));
    std::sort(by_distance.begin(), by_distance.end());
    std::vector<int> seen_by;
    for (std::size_t j = 0; j < 3 && j < by_distance.size(); ++j) seen_by.push_back(by_distance[j].second);
    points.p_W.push_back(p);
    points.views.push_back(seen_by);
  }
  const SurfaceReconstruction result = reconstructSurface(points);
  const SurfaceMesh& mesh = result.mesh;
  for (int index : mesh.point_index)
    EXPECT_LT(static_cast<std::size_t>(index), first_outlier) << "outlier " << index << " is in the surface";
  EXPECT_EQ(surface_test::componentSizes(mesh).size(), 1u);
  EXPECT_LE(surface_test::openEdges(mesh), 10);
  std::printf("outliers: %d open edges\n", surface_test::openEdges(mesh));
  for (std::size_t i = first_outlier; i < points.p_W.size(); ++i)
    EXPECT_FALSE(result.labelling.isInside(points.p_W[i] + Eigen::Vector3d(0.01, 0.01, 0.01)));
}

}  // namespace
}  // namespace hsmap
