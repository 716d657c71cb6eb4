#include "pipelines/evaluate/band_limited_phase_correlation.h"

#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace hsmap {

PhaseCorrelation bandLimitedPhaseCorrelate(const cv::Mat& truth, const cv::Mat& produced,
                                           const cv::Mat& window, double cutoff_px) {
  if (truth.type() != CV_64F || produced.type() != CV_64F || window.type() != CV_64F ||
      truth.size() != produced.size() || truth.size() != window.size() || truth.empty()) {
    throw std::invalid_argument("bandLimitedPhaseCorrelate: expected three CV_64F images of one size");
  }
  if (!(std::isfinite(cutoff_px) && cutoff_px >= 0.0)) {
    throw std::invalid_argument("bandLimitedPhaseCorrelate: cutoff_px must be finite and >= 0");
  }
  PhaseCorrelation result;
  const int rows = truth.rows, cols = truth.cols;
  cv::Mat a, b, A, B, C;
  cv::multiply(truth, window, a);
  cv::multiply(produced, window, b);
  cv::dft(a, A, cv::DFT_COMPLEX_OUTPUT);
  cv::dft(b, B, cv::DFT_COMPLEX_OUTPUT);
  cv::mulSpectrums(B, A, C, 0, /*conjB=*/true);
  for (int u = 0; u < rows; ++u) {
    const double fu = double(u <= rows / 2 ? u : u - rows) / rows;
    auto* row = C.ptr<cv::Vec2d>(u);
    for (int v = 0; v < cols; ++v) {
      const double fv = double(v <= cols / 2 ? v : v - cols) / cols;
      const double f2 = cutoff_px > 0.0 ? (fu * fu + fv * fv) * cutoff_px * cutoff_px : 0.0;
      const double magnitude = std::hypot(row[v][0], row[v][1]);
      const double weight = std::exp(-0.5 * f2) / (magnitude + 1e-300 + 1e-12 * magnitude);
      row[v] *= magnitude > 0.0 ? weight : 0.0;
    }
  }
  cv::Mat surface;
  cv::idft(C, surface, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  cv::Point peak;
  cv::minMaxLoc(surface, nullptr, nullptr, nullptr, &peak);
  // Centroid of the 5 x 5 window around the peak, wrapping (the surface is
  // periodic).
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      const int y = ((peak.y + dy) % rows + rows) % rows, x = ((peak.x + dx) % cols + cols) % cols;
      const double value = surface.at<double>(y, x);
      sum += value;
      sx += value * dx;
      sy += value * dy;
    }
  }
  double x = peak.x + (sum != 0.0 ? sx / sum : 0.0);
  double y = peak.y + (sum != 0.0 ? sy / sum : 0.0);
  if (x > cols / 2.0) x -= cols;
  if (y > rows / 2.0) y -= rows;
  result.shift = cv::Point2d(x, y);
  result.response = sum;
  return result;
}

}  // namespace hsmap
