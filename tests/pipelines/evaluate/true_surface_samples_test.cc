// sampleTrueSurface: the true surface under the footprint's pixel centres, on
// a bounded lattice; footprintStride: the lattice's stride.
#include "pipelines/evaluate/true_surface_samples.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "core/util/input_error.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::flatSeabed;
using testing::writeLocalRaster;

TEST(FootprintStrideTest, IsTheSmallestStrideWithinTheBound) {
  EXPECT_EQ(footprintStride(200, 200, 200000), 1);
  EXPECT_EQ(footprintStride(200, 200, 40000), 1);
  EXPECT_EQ(footprintStride(200, 200, 39999), 2);  // 100 x 100
  // sqrt(40000 / 1000) = 6.3; 7 gives 29 x 29 = 841 samples, 6 gives 34 x 34 = 1156.
  EXPECT_EQ(footprintStride(200, 200, 1000), 7);
  // A 100 m x 5 m transect at 1 cm: 5 million pixels into 200k.
  EXPECT_EQ(footprintStride(10000, 500, 200000), 5);
  EXPECT_EQ(footprintStride(1, 1, 1), 1);
  EXPECT_THROW(footprintStride(0, 5, 10), std::invalid_argument);
  EXPECT_THROW(footprintStride(5, 5, 0), std::invalid_argument);
}

class TrueSurfaceSamplesTest : public ::testing::Test {
 protected:
  testing::TempFolder temp_;
};

TEST_F(TrueSurfaceSamplesTest, SamplesTheTopmostSurfaceUnderEveryValidPixelCentre) {
  // A surface sloping down to the east: down = 10 + 0.2 east. Under it, a
  // second flat surface that the vertical ray must not reach.
  PlyMesh scene = flatSeabed(-1.0, 1.0, -1.0, 1.0, 0.5, 0.0);
  for (Eigen::Vector3d& v : scene.vertices) v.z() = 10.0 + 0.2 * v.y();
  const PlyMesh below = flatSeabed(-1.0, 1.0, -1.0, 1.0, 1.0, 12.0);
  const int offset = static_cast<int>(scene.vertices.size());
  scene.vertices.insert(scene.vertices.end(), below.vertices.begin(), below.vertices.end());
  for (const Eigen::Vector3i& t : below.triangles) {
    scene.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  // 10 x 20 pixels of 5 cm from (north 0.4, east -0.5); the pixel (2, 3) is NaN.
  const auto hdr = temp_ / "reflectance.hdr";
  writeLocalRaster(hdr, 10, 20, 3, 0.4, -0.5, 0.05,
                   [](int row, int col) { return !(row == 2 && col == 3); });
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const TrueSurfaceSamples samples = sampleTrueSurface(caster, hdr);
  EXPECT_EQ(samples.stride, 1);
  EXPECT_EQ(samples.footprint_pixels, 199);
  EXPECT_EQ(samples.missed_pixels, 0);
  ASSERT_EQ(samples.points_W.size(), 199u);
  // Row-major order: the first sample is the centre of pixel (0, 0), the
  // last that of pixel (9, 19).
  EXPECT_NEAR(samples.points_W.front().x(), 0.4 - 0.025, 1e-12);
  EXPECT_NEAR(samples.points_W.front().y(), -0.5 + 0.025, 1e-12);
  EXPECT_NEAR(samples.points_W.back().x(), 0.4 - 9.5 * 0.05, 1e-12);
  EXPECT_NEAR(samples.points_W.back().y(), -0.5 + 19.5 * 0.05, 1e-12);
  for (const Eigen::Vector3d& p : samples.points_W) {
    EXPECT_NEAR(p.z(), 10.0 + 0.2 * p.y(), 1e-9);
  }
}

TEST_F(TrueSurfaceSamplesTest, KeepsToTheBoundWithARegularStride) {
  const PlyMesh scene = flatSeabed(-2.0, 2.0, -2.0, 2.0, 1.0, 5.0);
  const auto hdr = temp_ / "reflectance.hdr";
  writeLocalRaster(hdr, 200, 200, 1, 1.0, -1.0, 0.01, [](int, int) { return true; });
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const TrueSurfaceSamples samples = sampleTrueSurface(caster, hdr, 1000);
  EXPECT_EQ(samples.stride, 7);
  ASSERT_EQ(samples.points_W.size(), 29u * 29u);
  // Rows and columns 0, 7, 14, ...: the second sample is the centre of column 7.
  EXPECT_NEAR(samples.points_W[1].y() - samples.points_W[0].y(), 0.07, 1e-12);
  EXPECT_NEAR(samples.points_W[29].x() - samples.points_W[0].x(), -0.07, 1e-12);
}

TEST_F(TrueSurfaceSamplesTest, PixelsOutsideTheSceneAreCountedNotSampled) {
  const PlyMesh scene = flatSeabed(0.0, 1.0, 0.0, 1.0, 0.5, 5.0);
  const auto hdr = temp_ / "reflectance.hdr";
  // 2 x 4 pixels of 0.5 m from (north 1, east -1): the west half is off the scene.
  writeLocalRaster(hdr, 2, 4, 1, 1.0, -1.0, 0.5, [](int, int) { return true; });
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const TrueSurfaceSamples samples = sampleTrueSurface(caster, hdr);
  EXPECT_EQ(samples.footprint_pixels, 8);
  EXPECT_EQ(samples.missed_pixels, 4);
  EXPECT_EQ(samples.points_W.size(), 4u);
}

TEST_F(TrueSurfaceSamplesTest, ARasterNotInLocalWIsRefused) {
  const PlyMesh scene = flatSeabed(0.0, 1.0, 0.0, 1.0, 0.5, 5.0);
  const MeshRayCaster caster(scene.vertices, scene.triangles);
  const auto hdr = temp_ / "reflectance.hdr";
  writeLocalRaster(hdr, 2, 2, 1, 1.0, 0.0, 0.5, [](int, int) { return true; });
  EnviHeader header = readEnviHeader(hdr);
  header.map_info->projection = "UTM";
  header.map_info->zone = 31;
  writeEnviHeader(hdr, header);
  EXPECT_THROW(sampleTrueSurface(caster, hdr), InputError);
  header.map_info.reset();
  writeEnviHeader(hdr, header);
  EXPECT_THROW(sampleTrueSurface(caster, hdr), InputError);
}

}  // namespace
}  // namespace hsmap
