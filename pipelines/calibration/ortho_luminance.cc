#include "pipelines/calibration/ortho_luminance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace hsmap {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr double kBinWidthNm = 20.0;

}  // namespace

cv::Mat rgbLuminance(const cv::Mat& bgra) {
  if (bgra.type() != CV_8UC4) throw std::invalid_argument("rgbLuminance: expected CV_8UC4");
  cv::Mat luma(bgra.size(), CV_32F);
  for (int r = 0; r < bgra.rows; ++r) {
    const cv::Vec4b* in = bgra.ptr<cv::Vec4b>(r);
    float* out = luma.ptr<float>(r);
    for (int c = 0; c < bgra.cols; ++c) {
      out[c] = in[c][3] == 0 ? kNaN : float(0.114 * in[c][0] + 0.587 * in[c][1] + 0.299 * in[c][2]);
    }
  }
  return luma;
}

BandCombination hyperspectralLuminance(const EnviReader& ortho,
                                       const std::vector<double>& wavelengths_nm,
                                       const cv::Mat& rgb_luma,
                                       const ExtrinsicRefinementOptions& options) {
  const int bands = ortho.bands(), cols = ortho.samples(), rows = ortho.lines();
  if (int(wavelengths_nm.size()) != bands) {
    throw std::invalid_argument("hyperspectralLuminance: one wavelength per band expected");
  }
  if (rgb_luma.rows != rows || rgb_luma.cols != cols || rgb_luma.type() != CV_32F) {
    throw std::invalid_argument("hyperspectralLuminance: the RGB luminance is not on the grid");
  }
  // Bands in range, in bins of kBinWidthNm.
  std::vector<int> bin_of_band(bands, -1);
  const int bins =
      std::max(1, int(std::ceil((options.band_max_nm - options.band_min_nm) / kBinWidthNm)));
  std::vector<int> bin_count(bins, 0);
  for (int b = 0; b < bands; ++b) {
    const double w = wavelengths_nm[b];
    if (w < options.band_min_nm || w > options.band_max_nm) continue;
    const int bin = std::min(bins - 1, int((w - options.band_min_nm) / kBinWidthNm));
    bin_of_band[b] = bin;
    ++bin_count[bin];
  }
  std::vector<int> used_bins;
  for (int k = 0; k < bins; ++k)
    if (bin_count[k] > 0) used_bins.push_back(k);
  if (used_bins.empty()) {
    throw std::invalid_argument("hyperspectralLuminance: no band in [band_min_nm, band_max_nm]");
  }
  const int m = int(used_bins.size());
  std::vector<int> column_of_bin(bins, -1);
  for (int i = 0; i < m; ++i) column_of_bin[used_bins[i]] = i;

  // One pass: every pixel's bin means (m floats; NaN when a band is not finite).
  std::vector<float> bin_means(std::size_t(rows) * cols * m, kNaN);
  Eigen::MatrixXf line;
  std::vector<double> sums(m);
  for (int r = 0; r < rows; ++r) {
    ortho.readLine(r, line);  // bands x cols
    for (int c = 0; c < cols; ++c) {
      std::fill(sums.begin(), sums.end(), 0.0);
      bool ok = true;
      for (int b = 0; b < bands && ok; ++b) {
        if (bin_of_band[b] < 0) continue;
        const float v = line(b, c);
        if (!std::isfinite(v)) ok = false;
        sums[column_of_bin[bin_of_band[b]]] += v;
      }
      if (!ok) continue;
      float* out = &bin_means[(std::size_t(r) * cols + c) * m];
      for (int i = 0; i < m; ++i) out[i] = float(sums[i] / bin_count[used_bins[i]]);
    }
  }

  BandCombination result;
  Eigen::VectorXd bin_weights = Eigen::VectorXd::Zero(m);
  double offset = 0.0;
  // Fixed luminance-like weights: blue < 500, green < 570, red beyond.
  for (int i = 0; i < m; ++i) {
    const double centre = options.band_min_nm + (used_bins[i] + 0.5) * kBinWidthNm;
    bin_weights[i] = centre < 500.0 ? 0.114 : centre < 570.0 ? 0.587 : 0.299;
  }
  {
    double total = bin_weights.sum();
    bin_weights /= total;
  }
  if (options.fit_band_weights) {
    // Ridge least squares of [bins, 1] -> RGB luminance on a subsample.
    Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(m + 1, m + 1);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(m + 1);
    double sum_y = 0.0, sum_y2 = 0.0;
    std::int64_t n = 0;
    Eigen::VectorXd x(m + 1);
    for (int r = 0; r < rows; r += options.fit_stride_px) {
      for (int c = 0; c < cols; c += options.fit_stride_px) {
        const float y = rgb_luma.at<float>(r, c);
        const float* means = &bin_means[(std::size_t(r) * cols + c) * m];
        if (!std::isfinite(y) || !std::isfinite(means[0])) continue;
        for (int i = 0; i < m; ++i) x[i] = means[i];
        x[m] = 1.0;
        normal.selfadjointView<Eigen::Lower>().rankUpdate(x);
        rhs += x * double(y);
        sum_y += y;
        sum_y2 += double(y) * y;
        ++n;
      }
    }
    if (n >= 10 * (m + 1)) {
      normal.triangularView<Eigen::StrictlyUpper>() = normal.transpose();
      const double scale = normal.diagonal().head(m).mean();
      Eigen::MatrixXd regularised = normal;
      for (int i = 0; i < m; ++i) regularised(i, i) += options.ridge * scale;
      const Eigen::VectorXd solution = regularised.ldlt().solve(rhs);
      if (solution.allFinite()) {
        // R^2 = 1 - SSE / SST with SSE = w^T N w - 2 w^T b + sum y^2.
        const double sse = solution.dot(normal * solution) - 2.0 * solution.dot(rhs) + sum_y2;
        const double sst = sum_y2 - sum_y * sum_y / double(n);
        result.r2 = sst > 0.0 ? 1.0 - sse / sst : 0.0;
        bin_weights = solution.head(m);
        offset = solution[m];
        result.fitted = true;
      }
    }
  }
  result.offset = offset;
  result.weights.assign(bands, 0.0);
  for (int b = 0; b < bands; ++b) {
    if (bin_of_band[b] < 0) continue;
    result.weights[b] = bin_weights[column_of_bin[bin_of_band[b]]] / bin_count[bin_of_band[b]];
  }
  result.luma = cv::Mat(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r) {
    float* out = result.luma.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      const float* means = &bin_means[(std::size_t(r) * cols + c) * m];
      if (!std::isfinite(means[0])) {
        out[c] = kNaN;
        continue;
      }
      double value = offset;
      for (int i = 0; i < m; ++i) value += bin_weights[i] * means[i];
      out[c] = float(value);
    }
  }
  return result;
}

}  // namespace hsmap
