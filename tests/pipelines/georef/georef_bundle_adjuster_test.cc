#include "pipelines/georef/georef_bundle_adjuster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "tests/pipelines/georef/georef_test_scene.h"

namespace hsmap {
namespace {

using namespace georef_testing;

struct Scene {
  VisualMap map;                 // the start: truth moved by a small similarity, plus noise
  std::vector<SE3d> true_T_W_K;  // per keyframe
  std::vector<InsFixLink> links;
};

// Keyframes every 0.5 s over 30 s, landmarks on a rough seabed 2 m below
// the camera, observed with 0.5 px noise; the start is the truth seen
// through S_err (2 % scale, 1 degree, 0.3 m), as an INS alignment would leave it.
Scene makeScene() {
  Scene scene;
  const PinholeRadtanCamera camera(testCamera());
  std::mt19937 rng(11);
  std::normal_distribution<double> pixel_noise(0.0, 0.5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Sim3 S_err(1.02, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 180.0, Eigen::Vector3d(0.3, 0.5, 0.8).normalized())),
                   Eigen::Vector3d(0.3, -0.2, 0.1));
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 3000; ++i) {
    const double x = -2.0 + 16.0 * u(rng), y = -3.5 + 7.0 * u(rng);
    points.emplace_back(x, y, 10.3 + 0.2 * std::sin(2.0 * x) * std::cos(1.5 * y));
  }
  for (const auto& p : points) scene.map.addLandmark(0, S_err.apply(p));
  for (int k = 0; k <= 60; ++k) {
    const double t = 0.5 * k;
    const SE3d T_W_C = trueCamera(t);
    scene.true_T_W_K.push_back(T_W_C);
    const int id = scene.map.addKeyframe(k * 15, t, 0, S_err.transformPose(T_W_C));
    for (std::size_t l = 0; l < points.size(); ++l) {
      const Eigen::Vector3d p_C = T_W_C.inverse() * points[l];
      if (p_C.z() < 0.5) continue;
      Eigen::Vector2d pixel = camera.project(p_C);
      if (!camera.isInImage(pixel)) continue;
      pixel += Eigen::Vector2d(pixel_noise(rng), pixel_noise(rng));
      scene.map.addObservation(id, int(l), pixel);
    }
  }
  return scene;
}

// With and without INS attitude (then the level, along-track attitude is a
// weak prior and the positions and vision determine the rotation).
class GeorefBundleAdjuster : public ::testing::TestWithParam<bool> {};

TEST_P(GeorefBundleAdjuster, RecoversTheTrajectoryAndLeavesOutAFaultyFix) {
  const bool attitude = GetParam();
  Scene scene = makeScene();
  const double sigma_h = 0.1, sigma_d = 0.02;
  // Fix 17 is 0.8 m off: within the alignment's 1 m threshold, 8 sigma out.
  const InsBodyTrack ins(insFixes(sigma_h, sigma_d, 5, {{17, Eigen::Vector3d(0.0, 0.8, 0.0)}}), attitude);
  for (std::size_t i = 0; i < ins.fixes().size(); ++i) {
    const double t = ins.fixes()[i].t;
    const int k = int(std::lround(t / 0.5));
    // The camera at the fix time relative to the keyframe: exact here (the
    // front-end's relative motion), and non-trivial for fixes between keyframes.
    scene.links.push_back({int(i), k, scene.true_T_W_K[std::size_t(k)].inverse() * trueCamera(t)});
  }
  InsNoise noise;
  noise.sigma_horizontal_m = sigma_h;
  noise.sigma_depth_m = sigma_d;
  noise.sigma_attitude_rad = Eigen::Vector3d(0.05, 0.05, 0.2) * M_PI / 180.0;
  GeorefBundleOptions options;
  const GeorefBundleReport report = adjustGeoreferencedMap(
      scene.map, scene.links, ins, mountingT_B_C(), noise, testCamera(), options);

  ASSERT_EQ(report.rejected.size(), 1u);
  EXPECT_EQ(report.rejected[0].fix, 17);
  EXPECT_EQ(report.rejected[0].line_number, 19);
  EXPECT_EQ(report.rejected[0].stage, "bundle adjustment");
  EXPECT_NEAR(report.rejected[0].offset_m, 0.8, 0.1);
  EXPECT_EQ(report.solves, 2);
  EXPECT_EQ(report.position_factors, 30);  // the last solve, without the faulty fix
  EXPECT_EQ(report.attitude_factors, 30);
  EXPECT_EQ(report.attitude_measured, attitude);
  EXPECT_TRUE(report.last_solve.usable);

  double sum = 0.0, worst_angle = 0.0;
  for (std::size_t k = 0; k < scene.true_T_W_K.size(); ++k) {
    const SE3d& estimate = scene.map.keyframe(int(k)).T_F_C;
    sum += (estimate.t - scene.true_T_W_K[k].t).squaredNorm();
    worst_angle = std::max(worst_angle, angleDeg(estimate.q, scene.true_T_W_K[k].q));
  }
  const double rms = std::sqrt(sum / double(scene.true_T_W_K.size()));
  // 30 fixes of 0.1 m place a rigid, well-scaled map to about 0.1 / sqrt(30) = 2 cm.
  EXPECT_LT(rms, 0.05) << "keyframe position rms " << rms << " m";
  EXPECT_LT(worst_angle, attitude ? 0.2 : 0.5);
}

INSTANTIATE_TEST_SUITE_P(InsAttitude, GeorefBundleAdjuster, ::testing::Bool(),
                         [](const auto& info) { return info.param ? "measured" : "absent"; });

}  // namespace
}  // namespace hsmap
