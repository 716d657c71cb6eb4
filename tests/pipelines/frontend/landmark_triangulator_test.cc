#include "pipelines/frontend/landmark_triangulator.h"

#include <gtest/gtest.h>

#include "tests/pipelines/frontend/synthetic_scene.h"

namespace hsmap {
namespace {

using testing::observe;

std::vector<TriangulationView> viewsOf(const PinholeRadtanCamera& camera, const std::vector<SE3d>& poses,
                                       const Eigen::Vector3d& p_F) {
  std::vector<TriangulationView> views;
  for (const SE3d& T : poses) {
    TriangulationView v;
    v.T_F_C = T;
    EXPECT_TRUE(observe(camera, T, p_F, v.pixel, v.normalized));
    views.push_back(v);
  }
  return views;
}

TEST(LandmarkTriangulator, RecoversAPointSeenFromThreeViews) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  const Eigen::Vector3d p_F(0.3, -0.2, 2.1);
  const std::vector<SE3d> poses{SE3d(), SE3d(expSO3(Eigen::Vector3d(0.01, 0.02, 0.0)), Eigen::Vector3d(0.2, 0.0, 0.0)),
                                SE3d(expSO3(Eigen::Vector3d(-0.02, 0.0, 0.03)), Eigen::Vector3d(0.4, 0.05, 0.02))};
  const TriangulationResult result = triangulateLandmark(viewsOf(camera, poses, p_F), camera, {});
  ASSERT_TRUE(result.ok()) << toString(result.outcome);
  EXPECT_LT((result.p_F - p_F).norm(), 1e-9);
  EXPECT_LT(result.max_error_px, 1e-6);
  EXPECT_NEAR(result.parallax_rad, std::acos((p_F - poses[0].t).normalized().dot((p_F - poses[2].t).normalized())), 1e-9);
}

TEST(LandmarkTriangulator, RejectsAPointWithTooLittleParallax) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  const Eigen::Vector3d p_F(0.3, -0.2, 2.1);
  // 1 cm baseline at 2 m: 0.3 degrees of parallax, below the 1.5 degree default.
  const std::vector<SE3d> poses{SE3d(), SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.01, 0.0, 0.0))};
  const TriangulationResult result = triangulateLandmark(viewsOf(camera, poses, p_F), camera, {});
  EXPECT_EQ(result.outcome, TriangulationOutcome::low_parallax);
  // The same views pass with a limit below their parallax.
  TriangulationLimits loose;
  loose.min_angle_rad = 0.001;
  EXPECT_TRUE(triangulateLandmark(viewsOf(camera, poses, p_F), camera, loose).ok());
}

TEST(LandmarkTriangulator, RejectsAnInconsistentTrackByItsReprojectionError) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  const Eigen::Vector3d p_F(0.3, -0.2, 2.1);
  const std::vector<SE3d> poses{SE3d(), SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.3, 0.0, 0.0)),
                                SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.6, 0.0, 0.0))};
  auto views = viewsOf(camera, poses, p_F);
  // The middle view slid 8 px along y (off the epipolar lines): no point fits all three.
  views[1].pixel.y() += 8.0;
  views[1].normalized = camera.unproject(views[1].pixel)->head<2>() / camera.unproject(views[1].pixel)->z();
  const TriangulationResult result = triangulateLandmark(views, camera, {});
  EXPECT_EQ(result.outcome, TriangulationOutcome::reprojection);
  EXPECT_GT(result.max_error_px, 2.0);
}

TEST(LandmarkTriangulator, RejectsAPointBehindACamera) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  // Two cameras facing each other's backs along x: rays meet behind the second.
  std::vector<TriangulationView> views(2);
  views[0].T_F_C = SE3d();
  views[0].normalized = {0.1, 0.0};
  views[0].pixel = camera.project(Eigen::Vector3d(0.1, 0.0, 1.0));
  views[1].T_F_C = SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.0, 5.0));
  views[1].normalized = {-0.1, 0.0};
  views[1].pixel = camera.project(Eigen::Vector3d(-0.1, 0.0, 1.0));
  const TriangulationResult result = triangulateLandmark(views, camera, {});
  EXPECT_EQ(result.outcome, TriangulationOutcome::behind_camera);
}

}  // namespace
}  // namespace hsmap
