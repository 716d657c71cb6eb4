#include "pipelines/frontend/lamp_light_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "pipelines/frontend/corner_detector.h"
#include "pipelines/frontend/klt_tracker.h"

namespace hsmap {
namespace {

constexpr int kWidth = 480, kHeight = 320;

// A large blurred random texture (the seabed), from which frames are cut.
cv::Mat seabed() {
  cv::Mat noise(1400, 1400, CV_32F);
  cv::RNG rng(11);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.0);
  cv::normalize(noise, noise, 0.15, 1.0, cv::NORM_MINMAX);
  return noise;
}

// The lamps' light: bright above the centre, falling off towards the
// bottom and the sides (like the presets' camera), scaled to mean 1.
cv::Mat lampLight() {
  cv::Mat light(kHeight, kWidth, CV_32F);
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) {
      const double du = (u - 0.5 * kWidth) / (0.45 * kWidth), dv = (v - 0.35 * kHeight) / (0.6 * kHeight);
      light.at<float>(v, u) = float(0.25 + std::exp(-(du * du + dv * dv)));
    }
  }
  return light / cv::mean(light)[0];
}

// The seabed seen at sub-pixel offset (x, y) of the texture, under `light`, in 8 bits.
cv::Mat frameAt(const cv::Mat& ground, const cv::Mat& light, double x, double y) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -x, 0, 1, -y);
  cv::Mat view;
  cv::warpAffine(ground, view, shift, cv::Size(kWidth, kHeight), cv::INTER_CUBIC);
  cv::Mat lit = view.mul(light) * 150.0, out;
  lit.convertTo(out, CV_8U);
  return out;
}

// 120 frames of the seabed at random places, as a survey samples them.
std::vector<cv::Mat> framesOfDifferentGround(const cv::Mat& ground, const cv::Mat& light, unsigned seed) {
  std::vector<cv::Mat> frames;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> offset(0.0, 850.0);
  for (int k = 0; k < 120; ++k) frames.push_back(frameAt(ground, light, offset(rng), offset(rng)));
  return frames;
}

TEST(LampLightField, RecoversTheLightFromFramesOfDifferentGround) {
  const cv::Mat ground = seabed(), light = lampLight();
  const cv::Mat field = lampLightFieldFromFrames(framesOfDifferentGround(ground, light, 3), 8.0);
  ASSERT_EQ(field.size(), light.size());
  EXPECT_NEAR(cv::mean(field)[0], 1.0, 1e-6);
  // Away from the border (where the blur reflects), within 5 % of the light.
  double worst = 0.0;
  for (int v = 24; v < kHeight - 24; ++v) {
    for (int u = 24; u < kWidth - 24; ++u) {
      worst = std::max(worst, std::abs(field.at<float>(v, u) / light.at<float>(v, u) - 1.0));
    }
  }
  EXPECT_LT(worst, 0.05);
}

TEST(LampLightField, DividingByTheLightGivesTheGroundBack) {
  const cv::Mat ground = seabed(), light = lampLight();
  const cv::Mat lit = frameAt(ground, light, 100.0, 200.0);
  const cv::Mat unlit = frameAt(ground, cv::Mat(light.size(), CV_32F, cv::Scalar(1.0)), 100.0, 200.0);
  const cv::Mat corrected = removeLampLight(lit, light);
  cv::Mat difference;
  cv::absdiff(corrected, unlit, difference);
  // Only the 8-bit rounding of the lit frame, amplified where it is dark.
  double worst = 0.0;
  cv::minMaxLoc(difference, nullptr, &worst);
  EXPECT_LE(worst, 3.0);
  EXPECT_LT(cv::mean(difference)[0], 0.5);
}

// The reason for the correction: under a light fixed in the image, frame-
// to-frame tracks fall short of the motion. Five frames of 6 px along v.
double meanShortfallAlongMotion(const cv::Mat& ground, const cv::Mat& light, const cv::Mat* field) {
  const FrontendOptions options;
  const KltTracker tracker(options, kWidth);
  const GridCornerDetector detector(options, kWidth, kHeight);
  const double step = 6.0;
  auto prepared = [&](int k) {
    cv::Mat frame = frameAt(ground, light, 300.0, 300.0 - step * k);
    return field ? removeLampLight(frame, *field) : frame;
  };
  cv::Mat previous = prepared(0);
  std::vector<cv::Point2f> points = detector.detect(previous, {});
  const std::vector<cv::Point2f> start = points;
  std::vector<bool> alive(points.size(), true);
  const int frames = 5;
  for (int k = 1; k <= frames; ++k) {
    const cv::Mat next = prepared(k);
    std::vector<cv::Point2f> guesses = points, tracked;
    for (auto& g : guesses) g.y += float(step);
    const std::vector<bool> good =
        tracker.track(tracker.buildPyramid(previous), tracker.buildPyramid(next), points, guesses, tracked);
    for (std::size_t i = 0; i < points.size(); ++i) alive[i] = alive[i] && good[i];
    points = tracked;
    previous = next;
  }
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!alive[i] || start[i].y > kHeight - 60) continue;
    sum += (start[i].y + step * frames) - points[i].y;
    ++count;
  }
  EXPECT_GT(count, 100);
  return sum / count;
}

TEST(LampLightField, TracksNoLongerFallShortOfTheMotionOnceTheLightIsRemoved) {
  const cv::Mat ground = seabed(), light = lampLight();
  const cv::Mat field = lampLightFieldFromFrames(framesOfDifferentGround(ground, light, 5), 8.0);
  const double raw = meanShortfallAlongMotion(ground, light, nullptr);
  const double corrected = meanShortfallAlongMotion(ground, light, &field);
  const double unlit = meanShortfallAlongMotion(ground, cv::Mat(light.size(), CV_32F, cv::Scalar(1.0)), nullptr);
  // Under the light the tracks lag measurably; with it divided out they
  // do no worse than under a uniform light, and far better than before.
  EXPECT_GT(raw, 0.01) << "corrected " << corrected << ", unlit " << unlit;
  EXPECT_LT(std::abs(corrected), 0.25 * raw) << "unlit " << unlit;
}

TEST(LampLightField, RejectsFramesOfAnotherSizeAndEmptyInput) {
  EXPECT_THROW(lampLightFieldFromFrames({}, 8.0), std::invalid_argument);
  std::vector<cv::Mat> frames{cv::Mat(10, 20, CV_8U, cv::Scalar(9)), cv::Mat(11, 20, CV_8U, cv::Scalar(9))};
  EXPECT_THROW(lampLightFieldFromFrames(frames, 8.0), std::invalid_argument);
  try {
    removeLampLight(cv::Mat(10, 20, CV_8U), cv::Mat(10, 21, CV_32F));
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "removeLampLight: the frame (20 x 10) and the light field (21 x 10) must be 8-bit grey "
                 "and float of one size");
  }
}

TEST(LampLightField, OptionsAreValidated) {
  FrontendOptions options;
  options.lamp_light_frames = 0;
  try {
    options.validate();
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "FrontendOptions.lamp_light_frames must be >= 1, got 0");
  }
  options = FrontendOptions{};
  options.lamp_light_blur_px = 0.0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
