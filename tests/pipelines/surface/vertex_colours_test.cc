#include "pipelines/surface/vertex_colours.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

PinholeRadtanParameters camera640() {
  PinholeRadtanParameters p;
  p.width = 640;
  p.height = 480;
  p.fx = p.fy = 500.0;
  p.cx = 320.0;
  p.cy = 240.0;
  p.distortion = {0.0, 0.0, 0.0, 0.0, 0.0};
  return p;
}

// Two frames of one flat colour each (RGB), listed in frames.csv.
RgbFrameSource twoFrames(const testing::TempFolder& folder) {
  const cv::Mat near(480, 640, CV_8UC3, cv::Scalar(30, 200, 10));  // BGR of RGB (10, 200, 30)
  const cv::Mat far(480, 640, CV_8UC3, cv::Scalar(90, 80, 70));    // RGB (70, 80, 90)
  EXPECT_TRUE(cv::imwrite((folder / "near.png").string(), near));
  EXPECT_TRUE(cv::imwrite((folder / "far.png").string(), far));
  testing::writeText(folder / "frames.csv", "file,t\nnear.png,1.0\nfar.png,2.0\n");
  return RgbFrameSource::fromFrameList(folder / "frames.csv");
}

TEST(VertexColours, EachVertexTakesTheClosestKeyframeThatSeesIt) {
  const testing::TempFolder folder("vertex-colours");
  const RgbFrameSource frames = twoFrames(folder);
  VisualMap map;
  // Both cameras look down (C's z along W's z) from 2 m and 3 m above the points.
  map.addKeyframe(0, 1.0, 0, SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -2)));
  map.addKeyframe(1, 2.0, 0, SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, -3)));
  VisibilityPoints points;
  points.c_W = {map.keyframe(0).T_F_C.t, map.keyframe(1).T_F_C.t};
  points.p_W = {Eigen::Vector3d(0.1, 0.0, 0.0),    // seen by both: the nearer wins
                Eigen::Vector3d(1.6, 0.0, 0.0),    // outside the near image (u = 720), inside the far one (u = 587)
                Eigen::Vector3d(40.0, 0.0, 0.0)};  // outside both
  points.views = {{0, 1}, {0, 1}, {0, 1}};
  SurfaceMesh mesh;
  mesh.vertices = points.p_W;
  mesh.point_index = {0, 1, 2};
  const VertexColours colours =
      colourVerticesFromKeyframes(mesh, points, map, frames, PinholeRadtanCamera(camera640()));
  ASSERT_EQ(colours.rgb.size(), 3u);
  EXPECT_EQ(colours.rgb[0], (Eigen::Matrix<std::uint8_t, 3, 1>(10, 200, 30)));
  EXPECT_EQ(colours.rgb[1], (Eigen::Matrix<std::uint8_t, 3, 1>(70, 80, 90)));
  EXPECT_EQ(colours.rgb[2], (Eigen::Matrix<std::uint8_t, 3, 1>(128, 128, 128)));
  EXPECT_EQ(colours.uncoloured, 1);
  EXPECT_EQ(colours.images_decoded, 2);
}

}  // namespace
}  // namespace hsmap
