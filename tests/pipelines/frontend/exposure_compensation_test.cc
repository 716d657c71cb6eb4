// Exposure compensation (exposure_compensation.h): the relative gain between
// two frames measured at the tracks' surroundings, robust to guesses a few
// pixels off, to snow-like blobs and to saturated pixels; and KLT through the
// front-end's CLAHE keeping its tracks across a 12 dB gain step once the next
// frame is brought to the previous one's exposure.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "pipelines/frontend/exposure_compensation.h"
#include "pipelines/frontend/frontend_options.h"
#include "pipelines/frontend/image_preprocessor.h"
#include "pipelines/frontend/klt_tracker.h"

namespace hsmap {
namespace {

constexpr int kWidth = 320, kHeight = 180;  // tiny's frames

// A seabed-like texture in linear grey levels: blurred noise, 10-60 DN, so
// that 12 dB (x3.98) more stays below saturation.
cv::Mat texture(unsigned seed) {
  cv::Mat noise(kHeight + 40, kWidth + 40, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.5);
  cv::normalize(noise, noise, 10.0, 60.0, cv::NORM_MINMAX);
  return noise;
}

// The texture seen shifted by `shift` pixels, times `gain`, as 8-bit.
cv::Mat view(const cv::Mat& texture, cv::Point2f shift, double gain) {
  // warpAffine: dst(q) = src(q - t); next(p + shift) = previous(p).
  const cv::Mat M = (cv::Mat_<double>(2, 3) << 1, 0, shift.x - 20.0, 0, 1, shift.y - 20.0);
  cv::Mat warped, out;
  cv::warpAffine(texture, warped, M, cv::Size(kWidth, kHeight), cv::INTER_CUBIC);
  warped.convertTo(out, CV_8U, gain);
  return out;
}

// Every `step` pixels, 16 px in from the border (boxes of 19 px stay inside).
std::vector<cv::Point2f> gridPoints(int step) {
  std::vector<cv::Point2f> points;
  for (int y = 16; y < kHeight - 16; y += step) {
    for (int x = 16; x < kWidth - 16; x += step) points.emplace_back(float(x), float(y));
  }
  return points;
}

const double kTwelveDb = std::pow(10.0, 12.0 / 20.0);
const cv::Point2f kShift(3.4f, 1.7f);

TEST(EstimateRelativeGain, RecoversATwelveDecibelStepFromGuessesAFewPixelsOff) {
  const cv::Mat tex = texture(1);
  const cv::Mat previous = view(tex, {0, 0}, 1.0), next = view(tex, kShift, kTwelveDb);
  const std::vector<cv::Point2f> points = gridPoints(12);
  std::vector<cv::Point2f> guesses;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> off(-2.0f, 2.0f);
  for (const auto& p : points) guesses.push_back(p + kShift + cv::Point2f(off(rng), off(rng)));
  const RelativeGain gain = estimateRelativeGain(previous, next, {}, {}, points, guesses, 9);
  std::cout << "12 dB step measured as " << gain.db() << " dB +- " << gain.sigma_db << " from "
            << gain.samples << " boxes\n";
  EXPECT_GE(gain.samples, int(points.size()) * 9 / 10);
  EXPECT_NEAR(gain.db(), 12.0, 0.1);
  EXPECT_LT(gain.sigma_db, 0.1);
  // No step: within its own noise of 0 dB.
  const RelativeGain none = estimateRelativeGain(previous, view(tex, kShift, 1.0), {}, {}, points, guesses, 9);
  EXPECT_LE(std::abs(none.db()), std::max(0.05, 3.0 * none.sigma_db));
}

TEST(EstimateRelativeGain, IgnoresSnowBlobsAndSaturatedPixels) {
  const cv::Mat tex = texture(2);
  const cv::Mat previous = view(tex, {0, 0}, 1.0);
  cv::Mat next = view(tex, kShift, kTwelveDb);
  // Marine snow: bright out-of-focus dots in the next frame only, in one box
  // of eight (more than `tiny` with 1000 particles/m3 has); and a saturated
  // patch (a lamp's hot spot). A contaminated box's ratio is far off, so it
  // only moves the median by a quantile of the clean boxes' spread (0.4 dB).
  const std::vector<cv::Point2f> points = gridPoints(12);
  for (std::size_t i = 0; i < points.size(); i += 8) {
    cv::circle(next, cv::Point(points[i] + kShift), 4, cv::Scalar(240), cv::FILLED, cv::LINE_AA);
  }
  const cv::Rect hot_spot(100, 60, 80, 50);
  next(hot_spot).setTo(250);
  cv::Mat next_saturated = cv::Mat::zeros(next.size(), CV_8U);
  next_saturated(hot_spot).setTo(255);
  std::vector<cv::Point2f> guesses;
  for (const auto& p : points) guesses.push_back(p + kShift);
  const RelativeGain gain = estimateRelativeGain(previous, next, {}, next_saturated, points, guesses, 9);
  std::cout << "with snow and a saturated patch: " << gain.db() << " dB from " << gain.samples << " boxes\n";
  EXPECT_NEAR(gain.db(), 12.0, 0.3);
  EXPECT_LT(gain.samples, int(points.size()));  // the saturated boxes were left out
}

TEST(EstimateRelativeGain, TooFewBoxesGiveNoStep) {
  const cv::Mat a = view(texture(3), {0, 0}, 1.0);
  const std::vector<cv::Point2f> points{{1.0f, 1.0f}, {50.0f, 50.0f}};  // one off the border
  const RelativeGain gain = estimateRelativeGain(a, a, {}, {}, points, points, 9);
  EXPECT_EQ(gain.samples, 1);
  EXPECT_EQ(gain.ratio, 1.0);
  EXPECT_THROW(estimateRelativeGain(a, cv::Mat(10, 10, CV_8U), {}, {}, points, points, 9), std::invalid_argument);
  EXPECT_THROW(estimateRelativeGain(a, a, cv::Mat(10, 10, CV_8U), {}, points, points, 9), std::invalid_argument);
}

TEST(CompensateGain, DividesRoundsAndClips) {
  cv::Mat linear(1, 3, CV_8U);
  linear.at<unsigned char>(0) = 201;
  linear.at<unsigned char>(1) = 100;
  linear.at<unsigned char>(2) = 255;
  const cv::Mat down = compensateGain(linear, 2.0), up = compensateGain(linear, 0.5);
  EXPECT_EQ(down.at<unsigned char>(0), 100);  // 100.5 rounds to even
  EXPECT_EQ(down.at<unsigned char>(1), 50);
  EXPECT_EQ(down.at<unsigned char>(2), 128);
  EXPECT_EQ(up.at<unsigned char>(1), 200);
  EXPECT_EQ(up.at<unsigned char>(2), 255);
  EXPECT_THROW(compensateGain(linear, 0.0), std::invalid_argument);
}

// Tracks from `previous` into `next`: how many pass KLT and its
// forward-backward check and land within 0.1 px of the true motion.
int accurateTracks(const KltTracker& klt, const cv::Mat& previous, const cv::Mat& next,
                   const std::vector<cv::Point2f>& points) {
  std::vector<cv::Point2f> guesses, tracked;
  for (const auto& p : points) guesses.push_back(p + kShift);
  const std::vector<bool> good = klt.track(klt.buildPyramid(previous), klt.buildPyramid(next), points, guesses, tracked);
  int accurate = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (good[i] && cv::norm(tracked[i] - (points[i] + kShift)) <= 0.1) ++accurate;
  }
  return accurate;
}

TEST(GainCompensation, KltThroughClaheKeepsItsTracksAcrossATwelveDecibelStep) {
  const FrontendOptions options;  // CLAHE on, as the front-end tracks
  const ImagePreprocessor preprocessor(options, kWidth, kHeight);
  const KltTracker klt(options, kWidth);
  const cv::Mat tex = texture(4);
  const cv::Mat previous_linear = view(tex, {0, 0}, 1.0);
  const cv::Mat next_linear = view(tex, kShift, kTwelveDb);
  const cv::Mat previous = preprocessor.equalise(previous_linear);
  std::vector<cv::Point2f> points;
  cv::goodFeaturesToTrack(previous, points, 300, 0.01, 8, cv::noArray(), 3);
  // Away from the border, so that every point stays in view.
  std::erase_if(points, [](const cv::Point2f& p) { return p.x < 20 || p.y < 20 || p.x > kWidth - 20 || p.y > kHeight - 20; });
  ASSERT_GE(points.size(), 100u);

  const int same_exposure = accurateTracks(klt, previous, preprocessor.equalise(view(tex, kShift, 1.0)), points);
  const int uncompensated = accurateTracks(klt, previous, preprocessor.equalise(next_linear), points);
  std::vector<cv::Point2f> guesses;
  for (const auto& p : points) guesses.push_back(p + kShift);
  const RelativeGain gain = estimateRelativeGain(previous_linear, next_linear, {}, {}, points, guesses, klt.windowPx());
  const int compensated =
      accurateTracks(klt, previous, preprocessor.equalise(compensateGain(next_linear, gain.ratio)), points);
  std::cout << points.size() << " tracks within 0.1 px: " << same_exposure << " at the same exposure, "
            << uncompensated << " across 12 dB, " << compensated << " across 12 dB compensated ("
            << gain.db() << " dB)\n";
  EXPECT_GE(compensated, same_exposure * 95 / 100);
  EXPECT_GT(compensated, uncompensated);
}

}  // namespace
}  // namespace hsmap
