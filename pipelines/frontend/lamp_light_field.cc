#include "pipelines/frontend/lamp_light_field.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "core/util/input_error.h"
#include "pipelines/frontend/image_preprocessor.h"
#include "pipelines/frontend/tracking_loss_monitor.h"

namespace hsmap {

namespace {

// `frame` added to `sum` (CV_32F; allocated at the first frame's size). The
// frames are summed as they are decoded, so the estimate holds one frame
// and the sum, not every sampled frame.
void addToSum(const cv::Mat& frame, cv::Mat& sum) {
  if (sum.empty()) sum = cv::Mat::zeros(frame.size(), CV_32F);
  if (frame.type() != CV_8UC1 || frame.size() != sum.size()) {
    throw std::invalid_argument("lampLightFieldFromFrames: every frame must be 8-bit grey of " +
                                std::to_string(sum.cols) + " x " + std::to_string(sum.rows));
  }
  cv::accumulate(frame, sum);
}

// The field from the sum of the frames: blurred, scaled to mean 1, floored.
cv::Mat fieldFromSum(const cv::Mat& sum, double blur_sigma_px) {
  if (!(blur_sigma_px > 0.0)) {
    throw std::invalid_argument("lampLightFieldFromFrames: the blur sigma must be > 0, got " +
                                std::to_string(blur_sigma_px));
  }
  cv::Mat field;
  cv::GaussianBlur(sum, field, cv::Size(0, 0), blur_sigma_px, blur_sigma_px, cv::BORDER_REFLECT);
  const double mean = cv::mean(field)[0];
  if (!(mean > 0.0)) {
    // Black frames only: nothing to correct.
    return cv::Mat(sum.size(), CV_32F, cv::Scalar(1.0));
  }
  field /= mean;
  return cv::max(field, kMinRelativeLight);
}

}  // namespace

cv::Mat lampLightFieldFromFrames(const std::vector<cv::Mat>& gray_frames, double blur_sigma_px) {
  if (gray_frames.empty()) throw std::invalid_argument("lampLightFieldFromFrames: no frames");
  cv::Mat sum;
  for (const cv::Mat& frame : gray_frames) addToSum(frame, sum);
  return fieldFromSum(sum, blur_sigma_px);
}

cv::Mat removeLampLight(const cv::Mat& gray, const cv::Mat& field) {
  if (gray.size() != field.size() || field.type() != CV_32F || gray.type() != CV_8UC1) {
    throw std::invalid_argument("removeLampLight: the frame (" + std::to_string(gray.cols) + " x " +
                                std::to_string(gray.rows) + ") and the light field (" +
                                std::to_string(field.cols) + " x " + std::to_string(field.rows) +
                                ") must be 8-bit grey and float of one size");
  }
  cv::Mat corrected;
  cv::divide(gray, field, corrected, 1.0, CV_8U);  // rounds and saturates
  return corrected;
}

LampLightEstimate estimateLampLight(const RgbFrameSource& source, int first, int last,
                                    const FrontendOptions& options, int width_px, int height_px) {
  const auto start = std::chrono::steady_clock::now();
  LampLightEstimate estimate;
  const int available = last - first + 1;
  const int wanted = std::min(available, options.lamp_light_frames);
  cv::Mat sum;
  for (int k = 0; k < wanted; ++k) {
    // Evenly over the survey, first and last included.
    const int i = wanted == 1 ? first : first + int((long long)(available - 1) * k / (wanted - 1));
    cv::Mat bgr;
    try {
      bgr = source.frame(i);
    } catch (const InputError&) {
      ++estimate.frames_skipped;  // the tracking pass reports it
      continue;
    }
    const cv::Mat gray = ImagePreprocessor::grey(bgr);
    if (gray.cols != width_px || gray.rows != height_px) {
      throw std::invalid_argument("frame " + std::to_string(i) + " is " + std::to_string(gray.cols) +
                                  " x " + std::to_string(gray.rows) + ", the camera " +
                                  std::to_string(width_px) + " x " + std::to_string(height_px));
    }
    if (textureProblem(ImagePreprocessor::measure(gray), options)) {
      ++estimate.frames_skipped;
      continue;
    }
    addToSum(gray, sum);
    ++estimate.frames_used;
  }
  char text[200];
  if (estimate.frames_used < options.lamp_light_min_frames) {
    std::snprintf(text, sizeof(text),
                  "lamp light not corrected: %d usable frames of %d sampled (need %d, or the mean "
                  "keeps the seabed's texture)",
                  estimate.frames_used, wanted, options.lamp_light_min_frames);
    estimate.note = text;
  } else {
    estimate.field = fieldFromSum(sum, options.lamp_light_blur_px * options.sizeScale(width_px));
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(estimate.field, &lo, &hi);
    estimate.brightest_to_darkest = hi / lo;
    std::snprintf(text, sizeof(text),
                  "lamp light corrected: field from %d frames (%d left out), brightest/darkest %.1f",
                  estimate.frames_used, estimate.frames_skipped, estimate.brightest_to_darkest);
    estimate.note = text;
  }
  estimate.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return estimate;
}

}  // namespace hsmap
