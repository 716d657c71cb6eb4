// Motion blur (rgb.exposure_s, rgb_motion_blur.h): the sub-frame rule, and a
// blurred frame of a moving camera is the instantaneous frame smeared along
// the motion by speed x exposure x focal / distance pixels.
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/survey.h"
#include "core/survey/survey_truth.h"
#include "pipelines/simulate/rgb_motion_blur.h"
#include "pipelines/simulate/simulate_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

TEST(RgbMotionBlur, SubframesAreCentredOnTheFrameTimeAndHalfAPixelApart) {
  EXPECT_EQ(motionBlurSubframes(0.0), 1);
  EXPECT_EQ(motionBlurSubframes(0.4), 1);
  EXPECT_EQ(motionBlurSubframes(3.2), 7);  // rugged at 1/50 s: 0.4 m/s x 0.02 s x 800 px / 2 m
  EXPECT_EQ(motionBlurSubframes(1e6), kMaxSubframes);
  const std::vector<double> times = subframeTimes(10.0, 0.02, 4);
  ASSERT_EQ(times.size(), 4u);
  EXPECT_NEAR(times[0], 10.0 - 0.0075, 1e-12);
  EXPECT_NEAR(times[3], 10.0 + 0.0075, 1e-12);
  EXPECT_NEAR((times[0] + times[3]) / 2.0, 10.0, 1e-12);
  EXPECT_EQ(subframeTimes(10.0, 0.02, 1), std::vector<double>{10.0});
}

// The green channel as float.
cv::Mat green(const cv::Mat& bgr) {
  cv::Mat channel, out;
  cv::extractChannel(bgr, channel, 1);
  channel.convertTo(out, CV_32F);
  return out;
}

// `image` smeared along its columns by a box of `length_px` (continuous,
// centred): each tap weighs the overlap of its pixel with the box.
cv::Mat boxAlongColumns(const cv::Mat& image, double length_px) {
  const int reach = int(std::ceil(length_px / 2.0 + 0.5));
  cv::Mat kernel(2 * reach + 1, 1, CV_32F);
  for (int j = -reach; j <= reach; ++j) {
    const double overlap = std::min(j + 0.5, length_px / 2.0) - std::max(j - 0.5, -length_px / 2.0);
    kernel.at<float>(j + reach) = float(std::max(overlap, 0.0) / length_px);
  }
  cv::Mat out;
  cv::filter2D(image, out, CV_32F, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  return out;
}

TEST(RgbMotionBlur, BlurLengthIsSpeedTimesExposureTimesFocalOverDistance) {
  // A straight, level, steady pass over a flat seabed without noise: the
  // image moves along its columns (top of the image forward) at a constant rate.
  SimulationConfig config = *simulationPreset("tiny");
  config.scene.terrain = TerrainPreset::flat;
  config.motion.speed_m_s = 0.5;
  config.motion.speed_variation = 0.0;
  config.motion.roll_pitch_amplitude_deg = 0.0;
  config.motion.heading_wander_deg = 0.0;
  config.rgb.rate_hz = 5.0;
  config.rgb.camera = scaledRgbCamera(160, 90);
  config.rgb.read_noise_dn = 0.0;
  config.rgb.electrons_per_dn = 1e12;
  testing::TempFolder temp("motion_blur");
  std::ostringstream log;
  simulateSurvey(config, temp / "sharp", log);
  config.rgb.exposure_s = 0.1;
  simulateSurvey(config, temp / "blurred", log);

  const Survey sharp = loadSurvey(temp / "sharp");
  const Survey blurred = loadSurvey(temp / "blurred");
  const SurveyTruth truth = loadSurveyTruth(temp / "blurred");
  ASSERT_EQ(sharp.rgb.frameCount(), blurred.rgb.frameCount());
  const PlyMesh mesh = readPly(truth.scene_path);
  const MeshRayCaster scene(mesh.vertices, mesh.triangles);
  const double f = config.rgb.camera.fy;
  int checked = 0;
  for (int k = 1; k + 1 < blurred.rgb.frameCount(); ++k) {
    // Speed from the truth poses, distance along the optical axis to the seabed.
    const SE3d& T_W_C = truth.rgb_poses[k].T_W_X;
    const double speed = (truth.rgb_poses[k + 1].T_W_X.t - truth.rgb_poses[k - 1].T_W_X.t).norm() /
                         (truth.rgb_poses[k + 1].t - truth.rgb_poses[k - 1].t);
    const RayHit hit = scene.intersect(Ray{T_W_C.t, T_W_C.q * Eigen::Vector3d::UnitZ()});
    ASSERT_TRUE(hit.hit());
    const double expected_px = speed * config.rgb.exposure_s * f / hit.distance;
    ASSERT_GT(expected_px, 5.0);

    // The box length that best turns the sharp frame into the blurred one,
    // over the central half of the image (lamp light varies slowly there).
    const cv::Mat a = green(sharp.rgb.frame(k));
    const cv::Mat b = green(blurred.rgb.frame(k));
    const cv::Rect centre(a.cols / 4, a.rows / 4, a.cols / 2, a.rows / 2);
    double best_length = 0.0, best_error = 1e300;
    for (double length = 0.5 * expected_px; length <= 1.5 * expected_px; length += 0.02) {
      const cv::Mat diff = boxAlongColumns(a, length)(centre) - b(centre);
      const double error = diff.dot(diff);
      if (error < best_error) {
        best_error = error;
        best_length = length;
      }
    }
    EXPECT_NEAR(best_length, expected_px, 0.05 * expected_px)
        << "frame " << k << ": speed " << speed << " m/s, distance " << hit.distance << " m";
    // Blurring along the rows instead explains the blurred frame far worse.
    cv::Mat across;
    cv::transpose(boxAlongColumns(a.t(), best_length), across);
    const cv::Mat across_diff = across(centre) - b(centre);
    EXPECT_GT(across_diff.dot(across_diff), 3.0 * best_error) << "frame " << k;
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

}  // namespace
}  // namespace hsmap
