// The same points give the same mesh, to the bit and in the same order,
// whatever the heap looked like: `hsmap run --from surface` must reproduce a
// full run's mesh (docs/RUN.md, "Reproducing a run"). CGAL visits each facet
// of the tetrahedralisation from the cell of lower address, so without the
// extraction's own order the triangles came out in an order that followed
// the allocator.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "pipelines/surface/surface_reconstruction.h"
#include "tests/pipelines/surface/synthetic_scenes.h"

namespace hsmap {
namespace {

double ripples(double x, double y) { return 0.05 * std::sin(4.0 * x) * std::cos(3.0 * y); }

std::vector<Eigen::Vector3d> camerasAbove(double half, double height, int per_side) {
  std::vector<Eigen::Vector3d> cameras;
  for (int i = 0; i < per_side; ++i)
    for (int j = 0; j < per_side; ++j)
      cameras.emplace_back(-half + 2.0 * half * i / (per_side - 1), -half + 2.0 * half * j / (per_side - 1), height);
  return cameras;
}

TEST(SurfaceRepeat, TheSamePointsGiveTheSameMeshWhateverTheHeap) {
  const VisibilityPoints points =
      surface_test::sampleHeightField(ripples, 1.0, 3000, 0.002, camerasAbove(1.0, 2.0, 4), 5);
  const SurfaceMesh first = reconstructSurface(points).mesh;
  ASSERT_GT(first.triangles.size(), 1000u);
  std::vector<std::unique_ptr<char[]>> churn;
  for (int repeat = 1; repeat <= 3; ++repeat) {
    // Blocks of odd sizes held and freed between the runs move the
    // tetrahedralisation's cells elsewhere on the heap.
    for (int i = 0; i < 2000 * repeat; ++i) churn.emplace_back(new char[std::size_t(48 + (i * 37) % 400)]);
    for (std::size_t i = 0; i < churn.size(); i += 2) churn[i].reset();
    const SurfaceMesh again = reconstructSurface(points).mesh;
    ASSERT_EQ(again.vertices.size(), first.vertices.size()) << "repeat " << repeat;
    ASSERT_EQ(again.triangles.size(), first.triangles.size()) << "repeat " << repeat;
    std::size_t vertices_differing = 0, triangles_differing = 0;
    for (std::size_t v = 0; v < first.vertices.size(); ++v) vertices_differing += again.vertices[v] != first.vertices[v];
    for (std::size_t t = 0; t < first.triangles.size(); ++t) triangles_differing += again.triangles[t] != first.triangles[t];
    EXPECT_EQ(vertices_differing, 0u) << "repeat " << repeat;
    EXPECT_EQ(triangles_differing, 0u) << "repeat " << repeat;
  }
}

}  // namespace
}  // namespace hsmap
