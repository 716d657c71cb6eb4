#include "pipelines/frontend/exposure_compensation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hsmap {

namespace {

// Mean of the box centred on `p`; false when the box leaves the image or
// holds a saturated pixel (`saturated` non-zero; may be empty).
bool boxMean(const cv::Mat& image, const cv::Mat& saturated, const cv::Point2f& p, int half, double& mean) {
  const int cx = static_cast<int>(std::lround(p.x)), cy = static_cast<int>(std::lround(p.y));
  if (!(std::isfinite(p.x) && std::isfinite(p.y))) return false;
  if (cx - half < 0 || cy - half < 0 || cx + half >= image.cols || cy + half >= image.rows) return false;
  long sum = 0;
  for (int y = cy - half; y <= cy + half; ++y) {
    const unsigned char* row = image.ptr<unsigned char>(y);
    const unsigned char* mask = saturated.empty() ? nullptr : saturated.ptr<unsigned char>(y);
    for (int x = cx - half; x <= cx + half; ++x) {
      if (mask != nullptr && mask[x] != 0) return false;
      sum += row[x];
    }
  }
  const int side = 2 * half + 1;
  mean = double(sum) / double(side * side);
  return true;
}

double medianOf(std::vector<double> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(mid), values.end());
  return values[mid];
}

}  // namespace

double RelativeGain::db() const { return 20.0 * std::log10(ratio); }

RelativeGain estimateRelativeGain(const cv::Mat& previous, const cv::Mat& next,
                                  const cv::Mat& previous_saturated, const cv::Mat& next_saturated,
                                  const std::vector<cv::Point2f>& points,
                                  const std::vector<cv::Point2f>& guesses, int half_box_px,
                                  double min_mean_dn, int min_samples) {
  if (previous.type() != CV_8UC1 || next.type() != CV_8UC1 || previous.size() != next.size()) {
    throw std::invalid_argument("estimateRelativeGain: two 8-bit grey images of one size expected");
  }
  for (const cv::Mat* mask : {&previous_saturated, &next_saturated}) {
    if (!mask->empty() && (mask->type() != CV_8UC1 || mask->size() != previous.size())) {
      throw std::invalid_argument("estimateRelativeGain: a saturation mask must be 8-bit of the images' size");
    }
  }
  if (points.size() != guesses.size()) {
    throw std::invalid_argument("estimateRelativeGain: one guess per point expected");
  }
  if (half_box_px < 1) throw std::invalid_argument("estimateRelativeGain: half_box_px must be >= 1");
  std::vector<double> log_ratios;
  log_ratios.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    double a = 0.0, b = 0.0;
    if (!boxMean(previous, previous_saturated, points[i], half_box_px, a) ||
        !boxMean(next, next_saturated, guesses[i], half_box_px, b)) {
      continue;
    }
    if (a < min_mean_dn || b < min_mean_dn) continue;
    log_ratios.push_back(std::log(b / a));
  }
  RelativeGain gain;
  gain.samples = int(log_ratios.size());
  if (gain.samples < std::max(1, min_samples)) return gain;
  const double median = medianOf(log_ratios);
  std::vector<double> deviations;
  deviations.reserve(log_ratios.size());
  for (double r : log_ratios) deviations.push_back(std::abs(r - median));
  // Median's standard error for a normal sample: 1.2533 sigma / sqrt(n),
  // sigma = 1.4826 MAD.
  const double sigma_log = 1.2533 * 1.4826 * medianOf(std::move(deviations)) / std::sqrt(double(gain.samples));
  gain.ratio = std::exp(median);
  gain.sigma_db = 20.0 / std::log(10.0) * sigma_log;
  return gain;
}

cv::Mat compensateGain(const cv::Mat& linear, double ratio) {
  if (linear.type() != CV_8UC1) throw std::invalid_argument("compensateGain: an 8-bit grey image expected");
  if (!(ratio > 0.0 && std::isfinite(ratio))) {
    throw std::invalid_argument("compensateGain: the ratio must be finite and > 0");
  }
  cv::Mat out;
  linear.convertTo(out, CV_8U, 1.0 / ratio);  // rounds and saturates
  return out;
}

}  // namespace hsmap
