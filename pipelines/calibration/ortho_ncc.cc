#include "pipelines/calibration/ortho_ncc.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>

namespace hsmap {

namespace {

// Parabola through (-1, a), (0, b), (1, c): offset of the vertex in [-0.5, 0.5].
double parabolaPeak(double a, double b, double c) {
  const double denominator = a - 2.0 * b + c;
  if (!(denominator < 0.0)) return 0.0;
  return std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
}

}  // namespace

PreparedImage prepareForMatching(const cv::Mat& luma, double blur_sigma_px,
                                 double highpass_sigma_px) {
  return prepareForMatching(luma, cv::Point2d(blur_sigma_px, blur_sigma_px),
                            cv::Point2d(highpass_sigma_px, highpass_sigma_px));
}

PreparedImage prepareForMatching(const cv::Mat& luma, cv::Point2d blur_sigma_px,
                                 cv::Point2d highpass_sigma_px) {
  PreparedImage out;
  out.valid = cv::Mat(luma.size(), CV_8U);
  double sum = 0.0, sum2 = 0.0;
  std::int64_t n = 0;
  for (int r = 0; r < luma.rows; ++r) {
    const float* row = luma.ptr<float>(r);
    std::uint8_t* mask = out.valid.ptr<std::uint8_t>(r);
    for (int c = 0; c < luma.cols; ++c) {
      const bool ok = std::isfinite(row[c]);
      mask[c] = ok ? 255 : 0;
      if (ok) {
        sum += row[c];
        sum2 += double(row[c]) * row[c];
        ++n;
      }
    }
  }
  const double mean = n > 0 ? sum / double(n) : 0.0;
  out.stddev = n > 1 ? std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean)) : 0.0;
  out.blurred = luma.clone();
  out.blurred.setTo(cv::Scalar(mean), out.valid == 0);
  if (blur_sigma_px.x > 0.0 && blur_sigma_px.y > 0.0) {
    cv::GaussianBlur(out.blurred, out.blurred, cv::Size(0, 0), blur_sigma_px.x, blur_sigma_px.y,
                     cv::BORDER_REFLECT);
  }
  if (highpass_sigma_px.x > 0.0 && highpass_sigma_px.y > 0.0) {
    cv::Mat background;
    cv::GaussianBlur(out.blurred, background, cv::Size(0, 0), highpass_sigma_px.x,
                     highpass_sigma_px.y, cv::BORDER_REFLECT);
    out.blurred -= background;
    cv::Scalar mean, stddev;
    cv::meanStdDev(out.blurred, mean, stddev, out.valid);
    out.stddev = stddev[0];
  }
  return out;
}

PreparedImage downsampled(const PreparedImage& image, int factor) {
  if (factor <= 1) return image;
  const cv::Size size(image.blurred.cols / factor, image.blurred.rows / factor);
  PreparedImage out;
  if (size.width < 1 || size.height < 1) {
    out.blurred = cv::Mat::zeros(1, 1, CV_32F);
    out.valid = cv::Mat::zeros(1, 1, CV_8U);
    return out;
  }
  // The top-left size * factor pixels, so each coarse pixel averages
  // exactly factor x factor fine ones.
  const cv::Rect used(0, 0, size.width * factor, size.height * factor);
  cv::resize(image.blurred(used), out.blurred, size, 0.0, 0.0, cv::INTER_AREA);
  cv::Mat valid_fraction;
  cv::resize(image.valid(used), valid_fraction, size, 0.0, 0.0, cv::INTER_AREA);
  // INTER_AREA rounds the mean: 255 only when every fine pixel is 255 (one
  // empty pixel in a 2 x 2 block gives 191).
  out.valid = valid_fraction >= 255;
  cv::Scalar mean, stddev;
  cv::meanStdDev(out.blurred, mean, stddev, out.valid);
  out.stddev = stddev[0];
  return out;
}

bool allValid(const cv::Mat& valid, const cv::Rect& window) {
  return cv::countNonZero(valid(window)) == window.area();
}

std::optional<NccPeak> unambiguousPeak(const cv::Mat& scores, double min_ncc,
                                       double min_peak_margin, double exclusion_radius_px) {
  return unambiguousPeak(scores, min_ncc, min_peak_margin,
                         cv::Point2d(exclusion_radius_px, exclusion_radius_px));
}

std::optional<NccPeak> unambiguousPeak(const cv::Mat& scores, double min_ncc,
                                       double min_peak_margin, cv::Point2d exclusion_radius_px) {
  double best = 0.0;
  cv::Point peak;
  cv::minMaxLoc(scores, nullptr, &best, nullptr, &peak);
  if (!(best >= min_ncc)) return std::nullopt;
  if (peak.x <= 0 || peak.y <= 0 || peak.x >= scores.cols - 1 || peak.y >= scores.rows - 1) {
    return std::nullopt;
  }
  // Outside the ellipse (x/rx)^2 + (y/ry)^2 <= 1 around the peak.
  const double rx = std::max(exclusion_radius_px.x, 1e-9);
  const double ry = std::max(exclusion_radius_px.y, 1e-9);
  double second = -1.0;
  for (int r = 0; r < scores.rows; ++r) {
    const float* row = scores.ptr<float>(r);
    for (int c = 0; c < scores.cols; ++c) {
      const double dx = (c - peak.x) / rx, dy = (r - peak.y) / ry;
      if (dx * dx + dy * dy > 1.0) second = std::max(second, double(row[c]));
    }
  }
  if (second > best - min_peak_margin) return std::nullopt;
  NccPeak out;
  const float centre = scores.at<float>(peak.y, peak.x);
  out.x = peak.x + parabolaPeak(scores.at<float>(peak.y, peak.x - 1), centre,
                                scores.at<float>(peak.y, peak.x + 1));
  out.y = peak.y + parabolaPeak(scores.at<float>(peak.y - 1, peak.x), centre,
                                scores.at<float>(peak.y + 1, peak.x));
  out.ncc = best;
  return out;
}

}  // namespace hsmap
