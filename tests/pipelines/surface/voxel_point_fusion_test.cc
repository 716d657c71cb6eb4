// VoxelPointFusion merges agreeing depth maps into one point per voxel and
// drops what only one depth map saw.
#include "pipelines/surface/voxel_point_fusion.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hsmap {
namespace {

TEST(VoxelPointFusion, AveragesThePointsOfAVoxelAndKeepsTheirViews) {
  VoxelPointFusion fusion(0.01);
  fusion.add({0.0012, 0.0051, 0.0033}, 3, 4);
  fusion.add({0.0018, 0.0049, 0.0037}, 5, 4);
  fusion.add({0.0030, 0.0050, 0.0050}, 5, 6);
  const FusedPoints fused = fusion.extract(2);
  ASSERT_EQ(fused.p_W.size(), 1u);
  EXPECT_NEAR(fused.p_W[0].x(), 0.0020, 1e-12);
  EXPECT_NEAR(fused.p_W[0].y(), 0.0050, 1e-12);
  EXPECT_NEAR(fused.p_W[0].z(), 0.0040, 1e-12);
  EXPECT_EQ(fused.support[0], 2);  // references 3 and 5
  EXPECT_EQ(fused.views[0], (std::vector<int>{3, 4, 5, 6}));
  EXPECT_EQ(fused.keys[0], fusion.keyOf({0.005, 0.005, 0.005}));
  EXPECT_EQ(fusion.pointsAdded(), 3u);
}

TEST(VoxelPointFusion, DropsVoxelsOnlyOneDepthMapSaw) {
  VoxelPointFusion fusion(0.01);
  fusion.add({0.0, 0.0, 0.0}, 1, 2);
  fusion.add({0.001, 0.0, 0.0}, 1, 2);  // the same depth map twice: still support 1
  fusion.add({0.5, 0.5, 0.5}, 1, 2);
  fusion.add({0.501, 0.5, 0.5}, 7, 2);
  EXPECT_EQ(fusion.voxelCount(), 2u);
  const FusedPoints fused = fusion.extract(2);
  ASSERT_EQ(fused.p_W.size(), 1u);
  EXPECT_NEAR(fused.p_W[0].x(), 0.5005, 1e-12);
  EXPECT_EQ(fusion.extract(1).p_W.size(), 2u);
}

TEST(VoxelPointFusion, NegativeCoordinatesFallInTheirOwnVoxels) {
  VoxelPointFusion fusion(0.01);
  // -0.004 and +0.004 are in different voxels ([-0.01, 0) and [0, 0.01)).
  EXPECT_NE(fusion.keyOf({-0.004, 0, 0}), fusion.keyOf({0.004, 0, 0}));
  EXPECT_EQ(fusion.keyOf({-0.004, 0, 0}), fusion.keyOf({-0.006, 0, 0}));
  EXPECT_NE(fusion.keyOf({0, -0.004, 0}), fusion.keyOf({0, 0, -0.004}));
}

TEST(VoxelPointFusion, ResultDoesNotDependOnTheOrderOfDepthMaps) {
  VoxelPointFusion forward(0.02), backward(0.02);
  std::vector<std::pair<Eigen::Vector3d, int>> points;
  for (int i = 0; i < 200; ++i) {
    points.push_back({Eigen::Vector3d(0.013 * i, -0.007 * i, 1.0 + 0.001 * (i % 7)), i % 3});
  }
  for (const auto& [p, reference] : points) forward.add(p, reference, 9);
  for (int reference = 2; reference >= 0; --reference) {
    for (const auto& [p, r] : points) {
      if (r == reference) backward.add(p, reference, 9);
    }
  }
  const FusedPoints a = forward.extract(1), b = backward.extract(1);
  ASSERT_EQ(a.keys, b.keys);
  for (std::size_t i = 0; i < a.p_W.size(); ++i) EXPECT_LT((a.p_W[i] - b.p_W[i]).norm(), 1e-12);
}

TEST(VoxelPointFusion, KeepsAtMostMaxViews) {
  VoxelPointFusion fusion(0.01);
  for (int k = 0; k < 20; ++k) fusion.add({0, 0, 0}, k, k + 100);
  const FusedPoints fused = fusion.extract(2);
  ASSERT_EQ(fused.p_W.size(), 1u);
  EXPECT_EQ(int(fused.views[0].size()), VoxelPointFusion::kMaxViews);
  EXPECT_EQ(fused.support[0], 20);
}

TEST(VoxelPointFusion, RejectsANonPositiveVoxelSize) {
  EXPECT_THROW(VoxelPointFusion(0.0), std::invalid_argument);
  EXPECT_THROW(VoxelPointFusion(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
