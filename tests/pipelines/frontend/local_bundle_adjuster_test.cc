#include "pipelines/frontend/local_bundle_adjuster.h"

#include <gtest/gtest.h>

#include <random>

#include "tests/pipelines/frontend/synthetic_scene.h"

namespace hsmap {
namespace {

// Eight keyframes along a line over the synthetic seabed; every landmark
// observed (with 0.3 px noise) wherever it is in view.
struct Scene {
  VisualMap map;
  std::vector<SE3d> true_poses;
  std::vector<Eigen::Vector3d> true_points;
};

Scene makeScene(const PinholeRadtanCamera& camera) {
  Scene scene;
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (int k = 0; k < 8; ++k) {
    const SE3d T(expSO3(Eigen::Vector3d(0.01 * k, -0.005 * k, 0.01)), Eigen::Vector3d(0.0, -0.08 * k, 0.01 * k));
    scene.true_poses.push_back(T);
    scene.map.addKeyframe(k, 0.1 * k, 0, T);
  }
  for (const auto& p : testing::seabedPoints(300, 9)) {
    std::vector<std::pair<int, Eigen::Vector2d>> seen;
    for (int k = 0; k < 8; ++k) {
      Eigen::Vector2d pixel, normalized;
      if (testing::observe(camera, scene.true_poses[std::size_t(k)], p, pixel, normalized)) {
        seen.emplace_back(k, pixel + Eigen::Vector2d(noise(rng), noise(rng)));
      }
    }
    if (seen.size() < 3) continue;
    const int l = scene.map.addLandmark(0, p);
    scene.true_points.push_back(p);
    for (const auto& [k, pixel] : seen) scene.map.addObservation(k, l, pixel);
  }
  return scene;
}

TEST(LocalBundleAdjuster, PullsPerturbedWindowBackAndHoldsTheOlderKeyframes) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  Scene scene = makeScene(camera);
  // Window: the last five keyframes, perturbed; the first three stay exact.
  const std::vector<int> window{3, 4, 5, 6, 7};
  for (int k : window) {
    Keyframe& kf = scene.map.keyframe(k);
    kf.T_F_C = SE3d(kf.T_F_C.q * expSO3(Eigen::Vector3d(0.004, -0.003, 0.002)),
                    kf.T_F_C.t + Eigen::Vector3d(0.01, -0.008, 0.006));
  }
  std::mt19937 rng(1);
  std::normal_distribution<double> jitter(0.0, 0.01);
  for (std::size_t l = 0; l < scene.true_points.size(); ++l) {
    scene.map.landmark(int(l)).p_F += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  }
  LocalBundleAdjustmentOptions options;
  options.max_iterations = 10;
  const LocalBundleAdjustmentReport report = adjustLocalWindow(scene.map, window, camera, options);
  ASSERT_TRUE(report.usable);
  EXPECT_EQ(report.free_keyframes, 5);
  EXPECT_EQ(report.fixed_keyframes, 3);
  EXPECT_LT(report.final_cost, 0.1 * report.initial_cost);
  for (int k : {0, 1, 2}) {
    EXPECT_EQ((scene.map.keyframe(k).T_F_C.t - scene.true_poses[std::size_t(k)].t).norm(), 0.0);
  }
  for (int k : window) {
    EXPECT_LT((scene.map.keyframe(k).T_F_C.t - scene.true_poses[std::size_t(k)].t).norm(), 0.002) << k;
  }
  EXPECT_EQ(report.removed_observations, 0);
}

TEST(LocalBundleAdjuster, RemovesTheOutlierObservationsTheSolveRejects) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  Scene scene = makeScene(camera);
  // Corrupt one observation of each of ten landmarks by 25 px.
  int corrupted = 0;
  for (int k = 5; k < 8 && corrupted < 10; ++k) {
    for (auto& o : scene.map.keyframe(k).observations) {
      if (corrupted >= 10) break;
      if (o.landmark_id % 7 != 0) continue;
      o.pixel += Eigen::Vector2d(25.0, -10.0);
      ++corrupted;
    }
  }
  ASSERT_EQ(corrupted, 10);
  const std::size_t before = scene.map.observationCount();
  const LocalBundleAdjustmentReport report =
      adjustLocalWindow(scene.map, {3, 4, 5, 6, 7}, camera, LocalBundleAdjustmentOptions{});
  ASSERT_TRUE(report.usable);
  EXPECT_EQ(report.removed_observations, 10);
  EXPECT_EQ(scene.map.observationCount(), before - 10);
  // Every observation left reprojects within the outlier limit.
  for (const Keyframe& k : scene.map.keyframes()) {
    for (const auto& o : k.observations) {
      const Eigen::Vector3d p_C = k.T_F_C.inverse() * scene.map.landmark(o.landmark_id).p_F;
      EXPECT_LT((camera.project(p_C) - o.pixel).norm(), 3.0);
    }
  }
}

TEST(LocalBundleAdjuster, HoldsTheSegmentsFirstTwoKeyframesWhenNothingOlderSeesTheWindow) {
  const PinholeRadtanCamera camera(testing::syntheticIntrinsics());
  Scene scene = makeScene(camera);
  const SE3d first = scene.map.keyframe(0).T_F_C, second = scene.map.keyframe(1).T_F_C;
  const LocalBundleAdjustmentReport report =
      adjustLocalWindow(scene.map, {0, 1, 2, 3, 4, 5, 6, 7}, camera, LocalBundleAdjustmentOptions{});
  ASSERT_TRUE(report.usable);
  EXPECT_EQ(report.fixed_keyframes, 2);
  EXPECT_EQ(report.free_keyframes, 6);
  EXPECT_EQ((scene.map.keyframe(0).T_F_C.t - first.t).norm(), 0.0);
  EXPECT_EQ((scene.map.keyframe(1).T_F_C.t - second.t).norm(), 0.0);
}

}  // namespace
}  // namespace hsmap
