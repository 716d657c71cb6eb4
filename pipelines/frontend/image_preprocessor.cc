#include "pipelines/frontend/image_preprocessor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "pipelines/frontend/lamp_light_field.h"

namespace hsmap {

ImagePreprocessor::ImagePreprocessor(const FrontendOptions& options, int width_px, int height_px,
                                     cv::Mat lamp_light_field)
    : use_clahe_(options.use_clahe), lamp_light_field_(std::move(lamp_light_field)) {
  if (use_clahe_) {
    const int across = options.clahe_tiles_across;
    const int down = std::max(1, static_cast<int>(std::lround(across * double(height_px) / width_px)));
    clahe_ = cv::createCLAHE(options.clahe_clip_limit, cv::Size(across, down));
  }
}

cv::Mat ImagePreprocessor::grey(const cv::Mat& bgr) {
  cv::Mat gray;
  if (bgr.channels() == 3) {
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  } else if (bgr.channels() == 1) {
    gray = bgr.clone();
  } else {
    throw std::invalid_argument("ImagePreprocessor: expected a 1- or 3-channel 8-bit image");
  }
  return gray;
}

cv::Mat ImagePreprocessor::process(const cv::Mat& bgr, ImageQuality* quality, cv::Mat* linear,
                                   cv::Mat* saturated) const {
  const cv::Mat raw = grey(bgr);
  if (quality != nullptr) *quality = measure(raw);
  cv::Mat gray = lamp_light_field_.empty() ? raw : removeLampLight(raw, lamp_light_field_);
  if (linear != nullptr) *linear = gray;  // equalise() writes a new image
  if (saturated != nullptr) *saturated = raw >= 250;
  return equalise(gray);
}

cv::Mat ImagePreprocessor::equalise(const cv::Mat& linear) const {
  if (!use_clahe_) return linear;
  cv::Mat equalised;
  clahe_->apply(linear, equalised);
  return equalised;
}

ImageQuality ImagePreprocessor::measure(const cv::Mat& gray) {
  cv::Mat small;
  cv::resize(gray, small, cv::Size(), 0.25, 0.25, cv::INTER_NEAREST);
  cv::Scalar mean, stddev;
  cv::meanStdDev(small, mean, stddev);
  ImageQuality quality;
  quality.mean_dn = mean[0];
  quality.contrast_dn = stddev[0];
  cv::Mat saturated = small >= 250;
  quality.saturated_fraction =
      small.total() == 0 ? 0.0 : double(cv::countNonZero(saturated)) / double(small.total());
  return quality;
}

}  // namespace hsmap
