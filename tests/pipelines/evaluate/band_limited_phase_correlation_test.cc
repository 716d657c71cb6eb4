#include "pipelines/evaluate/band_limited_phase_correlation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace hsmap {
namespace {

constexpr int kSide = 64;

// A smooth random texture (blurred white noise), sampled with a sub-pixel
// shift: image(x, y) = texture(x - dx, y - dy).
cv::Mat shiftedTexture(unsigned seed, double dx, double dy) {
  constexpr int kFine = 4;  // generated at 4x the resolution, then area-averaged
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  cv::Mat fine(2 * kSide * kFine, 2 * kSide * kFine, CV_64F);
  for (int r = 0; r < fine.rows; ++r) {
    for (int c = 0; c < fine.cols; ++c) fine.at<double>(r, c) = noise(rng);
  }
  cv::GaussianBlur(fine, fine, cv::Size(), 2.0 * kFine);  // 2 px at the final scale
  // warpAffine maps dst(x) = src(x - t) for the forward translation t.
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, kFine * dx, 0, 1, kFine * dy);
  cv::Mat moved, coarse;
  cv::warpAffine(fine, moved, shift, fine.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  cv::resize(moved, coarse, cv::Size(2 * kSide, 2 * kSide), 0, 0, cv::INTER_AREA);
  cv::Mat patch = coarse(cv::Rect(kSide / 2, kSide / 2, kSide, kSide)).clone();
  cv::Scalar mean, sd;
  cv::meanStdDev(patch, mean, sd);
  return (patch - mean[0]) / sd[0];  // mean 0, standard deviation 1
}

cv::Mat hann() {
  cv::Mat window;
  cv::createHanningWindow(window, cv::Size(kSide, kSide), CV_64F);
  return window;
}

// One correlation's accuracy: the 5 x 5 centroid of a whitened (delta-like)
// peak is pulled towards the whole pixel by up to ~0.3 pixel, and the fixed
// Hann window weighs shifted content differently (~0.2 pixel for a few
// pixels of shift). ortho_metrics.h removes both by re-correlating at the
// current estimate until the correction vanishes.
double tolerance(double cutoff_px) { return cutoff_px > 0.0 ? 0.25 : 0.35; }

// Pixel-scale white speckle of standard deviation `sd`, independent per call.
cv::Mat withSpeckle(const cv::Mat& image, double sd, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sd);
  cv::Mat out = image.clone();
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) out.at<double>(r, c) += noise(rng);
  }
  return out;
}

// cv::phaseCorrelate (OpenCV 4.6) with a window gives different shifts for
// the same input from call to call; the metric must not.
TEST(BandLimitedPhaseCorrelation, IsDeterministicWithAndWithoutCutoff) {
  const cv::Mat truth = shiftedTexture(1, 0.0, 0.0), produced = shiftedTexture(1, 1.3, -0.6);
  for (const double cutoff : {0.0, 4.0}) {
    const PhaseCorrelation first = bandLimitedPhaseCorrelate(truth, produced, hann(), cutoff);
    for (int k = 0; k < 5; ++k) {
      const PhaseCorrelation again = bandLimitedPhaseCorrelate(truth, produced, hann(), cutoff);
      EXPECT_EQ(again.shift, first.shift) << cutoff;
      EXPECT_EQ(again.response, first.response) << cutoff;
    }
    EXPECT_NEAR(first.shift.x, 1.3, tolerance(cutoff)) << cutoff;
    EXPECT_NEAR(first.shift.y, -0.6, tolerance(cutoff)) << cutoff;
  }
}

TEST(BandLimitedPhaseCorrelation, RecoversAKnownShiftWithItsSign) {
  const cv::Mat truth = shiftedTexture(2, 0.0, 0.0);
  for (const cv::Point2d shift : {cv::Point2d(3.0, -2.0), cv::Point2d(-5.0, 4.0), cv::Point2d(0.0, 0.0)}) {
    const cv::Mat produced = shiftedTexture(2, shift.x, shift.y);
    for (const double cutoff : {0.0, 4.0}) {
      const PhaseCorrelation got = bandLimitedPhaseCorrelate(truth, produced, hann(), cutoff);
      EXPECT_NEAR(got.shift.x, shift.x, tolerance(cutoff)) << shift << " cutoff " << cutoff;
      EXPECT_NEAR(got.shift.y, shift.y, tolerance(cutoff)) << shift << " cutoff " << cutoff;
      EXPECT_GT(got.response, 0.5) << shift << " cutoff " << cutoff;
    }
  }
  // Identical images: the whole surface is the peak.
  EXPECT_NEAR(bandLimitedPhaseCorrelate(truth, truth, hann(), 4.0).response, 1.0, 0.02);
}

// The property the ortho metrics rely on: pixel-scale texture that the two
// images sample differently (independent speckle) throws plain phase
// correlation off, and the band limit ignores it.
TEST(BandLimitedPhaseCorrelation, IsLessDisturbedThanPlainByIndependentSpeckle) {
  double plain_error = 0.0, limited_error = 0.0;
  int plain_matches = 0, limited_matches = 0;
  const int trials = 20;
  for (int k = 0; k < trials; ++k) {
    const cv::Mat texture = shiftedTexture(100 + k, 0.0, 0.0);
    const cv::Mat moved = shiftedTexture(100 + k, 0.5, 0.25);
    const cv::Mat truth = withSpeckle(texture, 1.0, 1000 + k), produced = withSpeckle(moved, 1.0, 2000 + k);
    const PhaseCorrelation plain = bandLimitedPhaseCorrelate(truth, produced, hann(), 0.0);
    const PhaseCorrelation limited = bandLimitedPhaseCorrelate(truth, produced, hann(), 4.0);
    plain_error += std::hypot(plain.shift.x - 0.5, plain.shift.y - 0.25);
    limited_error += std::hypot(limited.shift.x - 0.5, limited.shift.y - 0.25);
    plain_matches += plain.response >= 0.3;
    limited_matches += limited.response >= 0.3;
  }
  EXPECT_LT(limited_error / trials, 0.5 * plain_error / trials);
  EXPECT_GT(limited_matches, plain_matches);
  EXPECT_GE(limited_matches, trials * 9 / 10);
}

TEST(BandLimitedPhaseCorrelation, RejectsMismatchedImagesAndBadCutoffs) {
  const cv::Mat a = shiftedTexture(3, 0.0, 0.0);
  EXPECT_THROW(bandLimitedPhaseCorrelate(a, a(cv::Rect(0, 0, 32, 32)).clone(), hann(), 4.0), std::invalid_argument);
  cv::Mat as_float;
  a.convertTo(as_float, CV_32F);
  EXPECT_THROW(bandLimitedPhaseCorrelate(a, as_float, hann(), 4.0), std::invalid_argument);
  EXPECT_THROW(bandLimitedPhaseCorrelate(a, a, hann(), -1.0), std::invalid_argument);
  EXPECT_THROW(bandLimitedPhaseCorrelate(a, a, hann(), std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
