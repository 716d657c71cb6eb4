#include "pipelines/hyperspectral/ortho_matching.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "pipelines/hyperspectral/ortho_accumulator.h"

namespace hsmap {

namespace {

// Parabola through (-1, a), (0, b), (1, c): offset of the vertex in [-0.5, 0.5].
double parabolaPeak(double a, double b, double c) {
  const double denominator = a - 2.0 * b + c;
  if (!(denominator < 0.0)) return 0.0;
  return std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
}

// Blurred copy with NaN replaced by the mean of the valid pixels, and the
// mask (255 valid) of the original.
struct PreparedImage {
  cv::Mat blurred;  // CV_32F
  cv::Mat valid;    // CV_8U
  double stddev = 0.0;
};

PreparedImage prepare(const cv::Mat& luma, double blur_sigma_px, double highpass_sigma_px) {
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
  if (blur_sigma_px > 0.0) {
    cv::GaussianBlur(out.blurred, out.blurred, cv::Size(0, 0), blur_sigma_px, blur_sigma_px,
                     cv::BORDER_REFLECT);
  }
  if (highpass_sigma_px > 0.0) {
    cv::Mat background;
    cv::GaussianBlur(out.blurred, background, cv::Size(0, 0), highpass_sigma_px, highpass_sigma_px,
                     cv::BORDER_REFLECT);
    out.blurred -= background;
    cv::Scalar mean, stddev;
    cv::meanStdDev(out.blurred, mean, stddev, out.valid);
    out.stddev = stddev[0];
  }
  return out;
}

bool allValid(const cv::Mat& valid, const cv::Rect& window) {
  return cv::countNonZero(valid(window)) == window.area();
}

// p_W at continuous grid position (col, row): bilinear over the four pixels
// around it, all of which must be hits.
std::optional<Eigen::Vector3d> interpolatedPoint(const RgbOrthoRenderer& renderer,
                                                 const Eigen::Vector2d& col_row) {
  const int c0 = int(std::floor(col_row.x()));
  const int r0 = int(std::floor(col_row.y()));
  const OrthoGrid& grid = renderer.grid();
  if (c0 < 0 || r0 < 0 || c0 + 1 >= grid.cols || r0 + 1 >= grid.rows) return std::nullopt;
  const RgbOrthoPatch patch = renderer.render(c0, r0, 2, 2);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c)
      if (!patch.hit(c, r)) return std::nullopt;
  const double a = col_row.x() - c0, b = col_row.y() - r0;
  return (1 - a) * (1 - b) * patch.point(0, 0) + a * (1 - b) * patch.point(1, 0) +
         (1 - a) * b * patch.point(0, 1) + a * b * patch.point(1, 1);
}

// A tie's UHI pixel (continuous line, sample) at continuous grid position
// (col, row): the ancillary layer interpolated bilinearly over the four
// pixels around it, when all four hold values of one pass (their lines
// within the span the accumulator interpolates over); nullopt otherwise.
// Taking the nearest pixel's values instead puts the tie up to half a pixel
// off along the track, and a gap-filled pixel's nearest source a whole one.

std::optional<Eigen::Vector2d> interpolatedLineSample(const cv::Mat& ancillary,
                                                      const Eigen::Vector2d& col_row) {
  const int c0 = int(std::floor(col_row.x()));
  const int r0 = int(std::floor(col_row.y()));
  if (c0 < 0 || r0 < 0 || c0 + 1 >= ancillary.cols || r0 + 1 >= ancillary.rows) return std::nullopt;
  const double a = col_row.x() - c0, b = col_row.y() - r0;
  Eigen::Vector2d value = Eigen::Vector2d::Zero();
  float line_min = std::numeric_limits<float>::infinity(), line_max = -line_min;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) {
      const cv::Vec4f& anc = ancillary.at<cv::Vec4f>(r0 + r, c0 + c);
      if (!std::isfinite(anc[0]) || !std::isfinite(anc[1])) return std::nullopt;
      line_min = std::min(line_min, anc[0]);
      line_max = std::max(line_max, anc[0]);
      const double weight = (c == 0 ? 1.0 - a : a) * (r == 0 ? 1.0 - b : b);
      value += weight * Eigen::Vector2d(anc[0], anc[1]);
    }
  }
  if (line_max - line_min > OrthoTileAccumulator::kMaxInterpolatedLineSpan) return std::nullopt;
  return value;
}

}  // namespace

OrthoMatchCounts matchOrthoImages(const cv::Mat& rgb_luma, const cv::Mat& hyper_luma,
                                  const cv::Mat& ancillary, const RgbOrthoRenderer& renderer,
                                  const ExtrinsicRefinementOptions& options,
                                  std::vector<ExtrinsicTiePoint>& tie_points) {
  options.validate();
  const OrthoGrid& grid = renderer.grid();
  if (rgb_luma.size() != hyper_luma.size() || rgb_luma.rows != grid.rows ||
      rgb_luma.cols != grid.cols || ancillary.size() != rgb_luma.size() ||
      ancillary.type() != CV_32FC4) {
    throw std::invalid_argument("matchOrthoImages: the images are not on the renderer's grid");
  }
  const PreparedImage rgb = prepare(rgb_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const PreparedImage hyper = prepare(hyper_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const int half = std::max(2, int(std::lround(0.5 * options.patch_size_m / grid.pixel_m)));
  const int radius = std::max(2, int(std::lround(options.search_radius_m / grid.pixel_m)));
  const int step = std::max(1, int(std::lround(options.patch_spacing_m / grid.pixel_m)));
  const int size = 2 * half + 1;
  const int margin = half + radius;
  const double exclusion2 = options.exclusion_radius_px * options.exclusion_radius_px;
  const double min_std = options.min_template_std * rgb.stddev;

  OrthoMatchCounts counts;
  cv::Mat scores;
  for (int cy = margin; cy + margin < grid.rows; cy += step) {
    for (int cx = margin; cx + margin < grid.cols; cx += step) {
      ++counts.patches;
      const cv::Rect templ_rect(cx - half, cy - half, size, size);
      const cv::Rect search_rect(cx - margin, cy - margin, size + 2 * radius, size + 2 * radius);
      if (!allValid(rgb.valid, templ_rect) || !allValid(hyper.valid, search_rect)) continue;
      const cv::Mat templ = rgb.blurred(templ_rect);
      cv::Scalar mean, stddev;
      cv::meanStdDev(templ, mean, stddev);
      if (stddev[0] < min_std || stddev[0] <= 0.0) continue;
      ++counts.textured;
      cv::matchTemplate(hyper.blurred(search_rect), templ, scores, cv::TM_CCOEFF_NORMED);
      double best = 0.0;
      cv::Point peak;
      cv::minMaxLoc(scores, nullptr, &best, nullptr, &peak);
      if (!(best >= options.min_ncc)) continue;
      if (peak.x <= 0 || peak.y <= 0 || peak.x >= scores.cols - 1 || peak.y >= scores.rows - 1) {
        continue;
      }
      double second = -1.0;
      for (int r = 0; r < scores.rows; ++r) {
        const float* row = scores.ptr<float>(r);
        for (int c = 0; c < scores.cols; ++c) {
          const double d2 = double(c - peak.x) * (c - peak.x) + double(r - peak.y) * (r - peak.y);
          if (d2 > exclusion2) second = std::max(second, double(row[c]));
        }
      }
      if (second > best - options.min_peak_margin) continue;
      const double dx =
          parabolaPeak(scores.at<float>(peak.y, peak.x - 1), scores.at<float>(peak.y, peak.x),
                       scores.at<float>(peak.y, peak.x + 1));
      const double dy =
          parabolaPeak(scores.at<float>(peak.y - 1, peak.x), scores.at<float>(peak.y, peak.x),
                       scores.at<float>(peak.y + 1, peak.x));
      ++counts.matched;
      const Eigen::Vector2d g(cx, cy);
      const Eigen::Vector2d h = g + Eigen::Vector2d(peak.x + dx - radius, peak.y + dy - radius);
      // The UHI pixel at the match (the ancillary layer interpolated at h)
      // saw the mesh point at the patch centre g. Where the layer cannot be
      // interpolated (a swath edge, two passes), the nearest pixel's values,
      // the RGB side moved by the same rounding.
      const Eigen::Vector2i h_pixel(int(std::lround(h.x())), int(std::lround(h.y())));
      if (!grid.contains(h_pixel)) continue;
      const cv::Vec4f& anc = ancillary.at<cv::Vec4f>(h_pixel.y(), h_pixel.x());
      if (!std::isfinite(anc[0]) || !std::isfinite(anc[1])) continue;
      const std::optional<Eigen::Vector2d> line_sample = interpolatedLineSample(ancillary, h);
      const Eigen::Vector2d g_moved = line_sample ? g : g + (h_pixel.cast<double>() - h);
      const std::optional<Eigen::Vector3d> p_W = interpolatedPoint(renderer, g_moved);
      if (!p_W) continue;
      ExtrinsicTiePoint tie;
      tie.line_position = line_sample ? line_sample->x() : double(anc[0]);
      tie.line = std::llround(tie.line_position);
      tie.sample = line_sample ? line_sample->y() : double(anc[1]);
      tie.range_m = std::isfinite(anc[2]) ? anc[2] : 0.0;
      tie.p_W = *p_W;
      tie.rgb_col_row = g;
      tie.hyper_col_row = h;
      tie.ncc = best;
      tie_points.push_back(tie);
      ++counts.tie_points;
    }
  }
  return counts;
}

}  // namespace hsmap
