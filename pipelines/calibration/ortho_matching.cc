#include "pipelines/calibration/ortho_matching.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "pipelines/calibration/coarse_ortho_shift.h"
#include "pipelines/products/ortho_accumulator.h"
#include "pipelines/calibration/ortho_ncc.h"

namespace hsmap {

namespace {

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
  const PreparedImage rgb =
      prepareForMatching(rgb_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const PreparedImage hyper =
      prepareForMatching(hyper_luma, options.blur_sigma_px, options.highpass_sigma_px);
  const int half = std::max(2, int(std::lround(0.5 * options.patch_size_m / grid.pixel_m)));
  const int radius = std::max(2, int(std::lround(options.search_radius_m / grid.pixel_m)));
  const int step = std::max(1, int(std::lround(options.patch_spacing_m / grid.pixel_m)));
  const int size = 2 * half + 1;
  const int margin = half + radius;
  const double min_std = options.min_template_std * rgb.stddev;
  const CoarseOrthoShift coarse(rgb, hyper, grid.pixel_m, options);
  const cv::Rect image_rect(0, 0, grid.cols, grid.rows);

  OrthoMatchCounts counts;
  counts.coarse_patches = coarse.patches();
  counts.coarse_matched = coarse.matched();
  counts.coarse_scale = coarse.scale();
  cv::Mat scores;
  for (int cy = margin; cy + margin < grid.rows; cy += step) {
    for (int cx = margin; cx + margin < grid.cols; cx += step) {
      ++counts.patches;
      const Eigen::Vector2d g(cx, cy);
      // The search window centred where the coarse step puts the content.
      const std::optional<Eigen::Vector2d> coarse_shift = coarse.shiftAt(g);
      const cv::Point offset = coarse_shift ? cv::Point(int(std::lround(coarse_shift->x())),
                                                        int(std::lround(coarse_shift->y())))
                                            : cv::Point(0, 0);
      const cv::Rect templ_rect(cx - half, cy - half, size, size);
      const cv::Rect search_rect(cx + offset.x - margin, cy + offset.y - margin, size + 2 * radius,
                                 size + 2 * radius);
      if ((search_rect & image_rect) != search_rect) continue;
      if (!allValid(rgb.valid, templ_rect) || !allValid(hyper.valid, search_rect)) continue;
      const cv::Mat templ = rgb.blurred(templ_rect);
      cv::Scalar mean, stddev;
      cv::meanStdDev(templ, mean, stddev);
      if (stddev[0] < min_std || stddev[0] <= 0.0) continue;
      ++counts.textured;
      if (offset != cv::Point(0, 0)) ++counts.shifted;
      cv::matchTemplate(hyper.blurred(search_rect), templ, scores, cv::TM_CCOEFF_NORMED);
      const std::optional<NccPeak> peak = unambiguousPeak(scores, options.min_ncc,
                                                          options.min_peak_margin,
                                                          options.exclusion_radius_px);
      if (!peak) continue;
      const double best = peak->ncc;
      ++counts.matched;
      const Eigen::Vector2d h =
          g + Eigen::Vector2d(offset.x + peak->x - radius, offset.y + peak->y - radius);
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
