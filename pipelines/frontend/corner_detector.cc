#include "pipelines/frontend/corner_detector.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace hsmap {

GridCornerDetector::GridCornerDetector(const FrontendOptions& options, int width_px, int height_px)
    : width_(width_px),
      height_(height_px),
      cells_x_(options.grid_cells_across),
      cells_y_(std::max(1, static_cast<int>(std::lround(options.grid_cells_across *
                                                        double(height_px) / width_px)))),
      cell_w_(double(width_px) / cells_x_),
      cell_h_(double(height_px) / cells_y_),
      max_per_cell_(options.max_corners_per_cell),
      min_distance_(std::max(3.0, options.min_corner_distance_px * options.sizeScale(width_px))),
      quality_(options.corner_quality) {}

int GridCornerDetector::cellOf(const cv::Point2f& p) const {
  const int cx = std::clamp(static_cast<int>(p.x / cell_w_), 0, cells_x_ - 1);
  const int cy = std::clamp(static_cast<int>(p.y / cell_h_), 0, cells_y_ - 1);
  return cy * cells_x_ + cx;
}

double GridCornerDetector::coverage(const std::vector<cv::Point2f>& points) const {
  std::vector<char> occupied(std::size_t(cells_x_ * cells_y_), 0);
  for (const auto& p : points) occupied[std::size_t(cellOf(p))] = 1;
  return double(std::count(occupied.begin(), occupied.end(), 1)) / double(occupied.size());
}

std::vector<cv::Point2f> GridCornerDetector::detect(const cv::Mat& gray,
                                                    const std::vector<cv::Point2f>& existing) const {
  std::vector<int> count(std::size_t(cells_x_ * cells_y_), 0);
  for (const auto& p : existing) ++count[std::size_t(cellOf(p))];
  cv::Mat mask(gray.size(), CV_8U, cv::Scalar(255));
  int wanted = 0;
  for (int cy = 0; cy < cells_y_; ++cy) {
    for (int cx = 0; cx < cells_x_; ++cx) {
      const int n = count[std::size_t(cy * cells_x_ + cx)];
      if (n >= max_per_cell_) {
        const cv::Point a(int(cx * cell_w_), int(cy * cell_h_));
        const cv::Point b(int((cx + 1) * cell_w_), int((cy + 1) * cell_h_));
        cv::rectangle(mask, a, b, cv::Scalar(0), cv::FILLED);
      } else {
        wanted += max_per_cell_ - n;
      }
    }
  }
  if (wanted == 0) return {};
  const int radius = static_cast<int>(std::ceil(min_distance_));
  for (const auto& p : existing) cv::circle(mask, p, radius, cv::Scalar(0), cv::FILLED);
  // A border of half a KLT window: corners there cannot be tracked far.
  const int border = std::max(4, radius / 2);
  cv::rectangle(mask, cv::Point(0, 0), cv::Point(width_ - 1, height_ - 1), cv::Scalar(0), border);

  std::vector<cv::Point2f> candidates;
  // Ask for more than needed: the strongest corners cluster in a few cells.
  // Images 640 px wide or more are searched at half resolution: the corner
  // response over the whole image is most of the cost, a quarter of the
  // pixels costs a quarter, and a corner of the half image is a corner of the
  // full one (KLT tracks it at full resolution from there).
  if (width_ >= 640) {
    cv::Mat half, half_mask;
    cv::resize(gray, half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
    cv::resize(mask, half_mask, half.size(), 0.0, 0.0, cv::INTER_NEAREST);
    cv::goodFeaturesToTrack(half, candidates, 4 * wanted, quality_, 0.5 * min_distance_, half_mask, 3, false);
    for (auto& p : candidates) p = cv::Point2f(2.0f * p.x + 0.5f, 2.0f * p.y + 0.5f);
  } else {
    cv::goodFeaturesToTrack(gray, candidates, 4 * wanted, quality_, min_distance_, mask, 3, false);
  }
  std::vector<cv::Point2f> accepted;
  accepted.reserve(std::size_t(wanted));
  for (const auto& p : candidates) {  // strongest first
    int& n = count[std::size_t(cellOf(p))];
    if (n >= max_per_cell_) continue;
    ++n;
    accepted.push_back(p);
  }
  // No sub-pixel refinement: KLT tracks the patch around the point, wherever
  // exactly the point sits in it.
  return accepted;
}

}  // namespace hsmap
