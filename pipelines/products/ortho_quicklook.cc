#include "pipelines/products/ortho_quicklook.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/io/atomic_file.h"

namespace hsmap {

std::array<int, 3> nearestRgbBands(const std::vector<double>& wavelengths_nm) {
  if (wavelengths_nm.empty()) throw std::invalid_argument("nearestRgbBands: no wavelengths");
  const std::array<double, 3> targets{640.0, 550.0, 460.0};
  std::array<int, 3> bands{};
  for (int k = 0; k < 3; ++k) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < wavelengths_nm.size(); ++b) {
      const double d = std::abs(wavelengths_nm[b] - targets[std::size_t(k)]);
      if (d < best) {
        best = d;
        bands[std::size_t(k)] = int(b);
      }
    }
  }
  return bands;
}

OrthoQuicklook::OrthoQuicklook(int rows, int cols, std::array<int, 3> rgb_bands, int max_side)
    : full_cols_(cols), bands_(rgb_bands) {
  if (rows <= 0 || cols <= 0 || max_side <= 0) {
    throw std::invalid_argument("OrthoQuicklook: sizes must be positive");
  }
  factor_ = std::max(1, std::max((rows + max_side - 1) / max_side, (cols + max_side - 1) / max_side));
  rows_ = (rows + factor_ - 1) / factor_;
  cols_ = (cols + factor_ - 1) / factor_;
  sums_.assign(std::size_t(rows_) * cols_ * 3, 0.0f);
  counts_.assign(std::size_t(rows_) * cols_ * 3, 0);
}

void OrthoQuicklook::addRow(int row, const float* band_major_row) {
  const int r = row / factor_;
  if (row < 0 || r >= rows_) throw std::out_of_range("OrthoQuicklook::addRow: row out of range");
  for (int k = 0; k < 3; ++k) {
    const float* band = band_major_row + std::size_t(bands_[std::size_t(k)]) * full_cols_;
    for (int c = 0; c < full_cols_; ++c) {
      const float v = band[c];
      if (!std::isfinite(v)) continue;
      const std::size_t i = (std::size_t(r) * cols_ + std::size_t(c / factor_)) * 3 + std::size_t(k);
      sums_[i] += v;
      ++counts_[i];
    }
  }
}

void OrthoQuicklook::write(const std::filesystem::path& png_path) const {
  const std::size_t pixels = std::size_t(rows_) * cols_;
  std::array<float, 3> low{}, high{};
  for (int k = 0; k < 3; ++k) {
    std::vector<float> values;
    for (std::size_t p = 0; p < pixels; ++p) {
      const std::size_t i = p * 3 + std::size_t(k);
      if (counts_[i] > 0) values.push_back(sums_[i] / float(counts_[i]));
    }
    if (values.empty()) continue;
    auto at = [&](double q) {
      const std::size_t n = std::min(values.size() - 1, std::size_t(q * double(values.size() - 1) + 0.5));
      std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(n), values.end());
      return values[n];
    };
    low[std::size_t(k)] = at(0.02);
    high[std::size_t(k)] = at(0.98);
  }
  // BGR for OpenCV: channel 0 = blue = k 2.
  cv::Mat image(rows_, cols_, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int r = 0; r < rows_; ++r) {
    auto* out = image.ptr<cv::Vec3b>(r);
    for (int c = 0; c < cols_; ++c) {
      const std::size_t p = std::size_t(r) * cols_ + c;
      if (counts_[p * 3] == 0 || counts_[p * 3 + 1] == 0 || counts_[p * 3 + 2] == 0) continue;
      for (int k = 0; k < 3; ++k) {
        const float v = sums_[p * 3 + std::size_t(k)] / float(counts_[p * 3 + std::size_t(k)]);
        const float span = high[std::size_t(k)] - low[std::size_t(k)];
        const float x = span > 0.0f ? (v - low[std::size_t(k)]) / span : 0.5f;
        out[c][2 - k] = cv::saturate_cast<unsigned char>(std::clamp(x, 0.0f, 1.0f) * 255.0f);
      }
    }
  }
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", image, bytes)) {
    throw std::runtime_error(png_path.string() + ": cannot encode the quick-look PNG");
  }
  AtomicFile file(png_path);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  file.commit();
}

}  // namespace hsmap
