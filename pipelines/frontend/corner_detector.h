#pragma once
// GridCornerDetector: Shi-Tomasi corners (cv::goodFeaturesToTrack) spread
// over a grid of square cells, so the image stays covered. A cell that
// already holds `max_corners_per_cell` tracks gets no new corner; elsewhere
// new corners keep `min_corner_distance` from existing tracks and from each
// other. One detection over the whole image (strongest corners first) is
// distributed to the cells, which costs one corner-response pass instead of
// one per cell.
//
// Corner strength is relative to the image's best corner (corner_quality),
// so it adapts to contrast; a black or flat image has no corner at all.

#include <opencv2/core.hpp>
#include <vector>

#include "pipelines/frontend/frontend_options.h"

namespace hsmap {

class GridCornerDetector {
 public:
  GridCornerDetector(const FrontendOptions& options, int width_px, int height_px);

  // New corners where `existing` points (current tracks) leave room.
  std::vector<cv::Point2f> detect(const cv::Mat& gray, const std::vector<cv::Point2f>& existing) const;

  // Fraction of the grid's cells holding at least one of `points`.
  double coverage(const std::vector<cv::Point2f>& points) const;

  int cellsAcross() const { return cells_x_; }
  int cellsDown() const { return cells_y_; }
  int cellOf(const cv::Point2f& p) const;

 private:
  int width_, height_;
  int cells_x_, cells_y_;
  double cell_w_, cell_h_;
  int max_per_cell_;
  double min_distance_;
  double quality_;
};

}  // namespace hsmap
