#include "core/util/median.h"
#include "pipelines/calibration/coarse_ortho_shift.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace hsmap {

namespace {

}  // namespace

CoarseOrthoShift::CoarseOrthoShift(const PreparedImage& rgb, const PreparedImage& hyper,
                                   double pixel_m, const ExtrinsicRefinementOptions& options)
    : min_matches_(options.coarse_min_matches) {
  if (!(options.coarse_pixel_m > 0.0)) return;
  const int factor = std::max(1, int(std::lround(options.coarse_pixel_m / pixel_m)));
  const PreparedImage rgb_c = downsampled(rgb, factor);
  const PreparedImage hyper_c = downsampled(hyper, factor);
  // A swath narrower than the search windows (1.2 m at the defaults) leaves
  // none of them wholly valid: try windows of half the size.
  for (const double scale : {1.0, 0.5}) {
    matchLattice(rgb_c, hyper_c, factor, pixel_m, scale, options);
    if (matched() >= min_matches_) break;
  }
}

void CoarseOrthoShift::matchLattice(const PreparedImage& rgb_c, const PreparedImage& hyper_c,
                                    int factor, double pixel_m, double scale,
                                    const ExtrinsicRefinementOptions& options) {
  centres_.clear();
  shifts_.clear();
  patches_ = 0;
  scale_ = scale;
  const double coarse_m = factor * pixel_m;
  const int half =
      std::max(2, int(std::lround(0.5 * scale * options.coarse_patch_size_m / coarse_m)));
  const int radius =
      std::max(2, int(std::lround(scale * options.coarse_search_radius_m / coarse_m)));
  const int step = std::max(1, int(std::lround(scale * options.coarse_spacing_m / coarse_m)));
  const int size = 2 * half + 1;
  const int margin = half + radius;
  // The lattice's exclusion disc is in fine pixels; at least 2 coarse ones.
  const double exclusion_px = std::max(2.0, options.exclusion_radius_px / factor);
  const double min_std = options.min_template_std * rgb_c.stddev;

  // A coarse pixel (x, y) covers fine pixels factor * x ... factor * x +
  // factor - 1: its centre is at fine factor * x + (factor - 1) / 2.
  const double centre_offset = 0.5 * (factor - 1);
  origin_x_ = factor * margin + centre_offset;
  origin_y_ = factor * margin + centre_offset;
  cell_px_ = double(factor * step);
  neighbourhood_px_ = options.coarse_neighbourhood_m / pixel_m;
  cells_x_ = rgb_c.blurred.cols > 2 * margin ? (rgb_c.blurred.cols - 2 * margin - 1) / step + 1 : 0;
  cells_y_ = rgb_c.blurred.rows > 2 * margin ? (rgb_c.blurred.rows - 2 * margin - 1) / step + 1 : 0;
  cell_of_.assign(std::size_t(cells_x_) * std::size_t(cells_y_), -1);

  cv::Mat scores;
  for (int j = 0; j < cells_y_; ++j) {
    for (int i = 0; i < cells_x_; ++i) {
      const int cx = margin + i * step, cy = margin + j * step;
      ++patches_;
      const cv::Rect templ_rect(cx - half, cy - half, size, size);
      const cv::Rect search_rect(cx - margin, cy - margin, size + 2 * radius, size + 2 * radius);
      if (!allValid(rgb_c.valid, templ_rect) || !allValid(hyper_c.valid, search_rect)) continue;
      const cv::Mat templ = rgb_c.blurred(templ_rect);
      cv::Scalar mean, stddev;
      cv::meanStdDev(templ, mean, stddev);
      if (stddev[0] < min_std || stddev[0] <= 0.0) continue;
      cv::matchTemplate(hyper_c.blurred(search_rect), templ, scores, cv::TM_CCOEFF_NORMED);
      const std::optional<NccPeak> peak =
          unambiguousPeak(scores, options.min_ncc, options.min_peak_margin, exclusion_px);
      if (!peak) continue;
      cell_of_[std::size_t(j) * cells_x_ + i] = int(centres_.size());
      centres_.emplace_back(factor * cx + centre_offset, factor * cy + centre_offset);
      shifts_.emplace_back(factor * (peak->x - radius), factor * (peak->y - radius));
    }
  }
}

std::optional<Eigen::Vector2d> CoarseOrthoShift::shiftAt(const Eigen::Vector2d& g) const {
  if (centres_.empty()) return std::nullopt;
  const int reach = int(std::ceil(neighbourhood_px_ / cell_px_));
  const int ci = int(std::lround((g.x() - origin_x_) / cell_px_));
  const int cj = int(std::lround((g.y() - origin_y_) / cell_px_));
  std::vector<double> xs, ys;
  for (int j = std::max(0, cj - reach); j <= std::min(cells_y_ - 1, cj + reach); ++j) {
    for (int i = std::max(0, ci - reach); i <= std::min(cells_x_ - 1, ci + reach); ++i) {
      const int index = cell_of_[std::size_t(j) * cells_x_ + i];
      if (index < 0 || (centres_[index] - g).norm() > neighbourhood_px_) continue;
      xs.push_back(shifts_[index].x());
      ys.push_back(shifts_[index].y());
    }
  }
  if (int(xs.size()) < min_matches_) return std::nullopt;
  return Eigen::Vector2d(median(xs), median(ys));
}

}  // namespace hsmap
