#include "pipelines/frontend/frame_pose_estimator.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/pipelines/frontend/synthetic_scene.h"

namespace hsmap {
namespace {

TEST(FramePoseEstimator, RecoversThePoseDespiteAQuarterOfOutliers) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  const SE3d T_F_C(expSO3(Eigen::Vector3d(0.03, -0.02, 0.1)), Eigen::Vector3d(0.2, -0.1, 0.05));
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<PoseCorrespondence> correspondences;
  std::vector<bool> is_outlier;
  for (const auto& p : testing::seabedPoints(300, 2)) {
    Eigen::Vector2d pixel, normalized;
    if (!testing::observe(camera, T_F_C, p, pixel, normalized)) continue;
    const bool outlier = u(rng) < 0.25;
    pixel += outlier ? Eigen::Vector2d(40.0 + 100.0 * u(rng), -30.0 - 80.0 * u(rng))
                     : Eigen::Vector2d(noise(rng), noise(rng));
    const auto ray = camera.unproject(pixel);
    if (!ray) continue;
    correspondences.push_back({p, ray->head<2>() / ray->z(), pixel});
    is_outlier.push_back(outlier);
  }
  // A prediction 5 cm and 3 degrees off, as a motion model might give.
  const SE3d prediction(T_F_C.q * expSO3(Eigen::Vector3d(0.05, 0.0, 0.0)), T_F_C.t + Eigen::Vector3d(0.05, 0.0, 0.0));
  const PoseEstimate estimate = estimateFramePose(correspondences, prediction, camera, PoseEstimatorOptions{});
  ASSERT_TRUE(estimate.ok) << estimate.failure;
  EXPECT_LT((estimate.T_F_C.t - T_F_C.t).norm(), 0.003);
  EXPECT_LT(testing::rotationAngleDeg(estimate.T_F_C.q, T_F_C.q), 0.05);
  int wrong = 0;
  for (std::size_t i = 0; i < correspondences.size(); ++i) wrong += estimate.inliers[i] == is_outlier[i] ? 1 : 0;
  EXPECT_LE(wrong, 2);
  EXPECT_LT(estimate.rms_error_px, 0.6);
}

TEST(FramePoseEstimator, MotionOnlyRefinementUsesTheLensModelThatPnPIgnores) {
  // Start from a pose 2 cm off: the refinement alone must bring it back to
  // the exact pose of noiseless distorted pixels.
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  const SE3d T_F_C(expSO3(Eigen::Vector3d(0.0, 0.02, -0.05)), Eigen::Vector3d(-0.1, 0.2, 0.0));
  std::vector<PoseCorrespondence> correspondences;
  for (const auto& p : testing::seabedPoints(100, 4)) {
    Eigen::Vector2d pixel, normalized;
    if (testing::observe(camera, T_F_C, p, pixel, normalized)) correspondences.push_back({p, normalized, pixel});
  }
  SE3d estimate(T_F_C.q, T_F_C.t + Eigen::Vector3d(0.02, -0.01, 0.0));
  ASSERT_TRUE(refinePoseMotionOnly(correspondences, std::vector<bool>(correspondences.size(), true), camera,
                                   PoseEstimatorOptions{}, estimate));
  EXPECT_LT((estimate.t - T_F_C.t).norm(), 1e-6);
}

TEST(FramePoseEstimator, FailsWithTooFewLandmarks) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  std::vector<PoseCorrespondence> correspondences;
  for (const auto& p : testing::seabedPoints(10, 4)) {
    Eigen::Vector2d pixel, normalized;
    if (testing::observe(camera, SE3d(), p, pixel, normalized)) correspondences.push_back({p, normalized, pixel});
  }
  const PoseEstimate estimate = estimateFramePose(correspondences, SE3d(), camera, PoseEstimatorOptions{});
  EXPECT_FALSE(estimate.ok);
  EXPECT_NE(estimate.failure.find("too few"), std::string::npos) << estimate.failure;
}

}  // namespace
}  // namespace hsmap
