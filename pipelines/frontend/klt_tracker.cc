#include "pipelines/frontend/klt_tracker.h"

#include <algorithm>
#include <cmath>
#include <opencv2/video/tracking.hpp>

namespace hsmap {

KltTracker::KltTracker(const FrontendOptions& options, int width_px)
    : levels_(options.klt_pyramid_levels),
      criteria_(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, options.klt_max_iterations,
                options.klt_epsilon),
      forward_backward_max_px_(options.forward_backward_max_px * options.errorScale(width_px)) {
  // Below 9 px a window holds too little texture for a stable 2x2 system.
  int window = static_cast<int>(std::lround(options.klt_window_px * options.sizeScale(width_px)));
  window = std::max(9, window | 1);
  window_px_ = window;
}

ImagePyramid KltTracker::buildPyramid(const cv::Mat& gray) const {
  ImagePyramid pyramid;
  cv::buildOpticalFlowPyramid(gray, pyramid, cv::Size(window_px_, window_px_), levels_, true);
  return pyramid;
}

std::vector<bool> KltTracker::track(const ImagePyramid& previous, const ImagePyramid& next,
                                    const std::vector<cv::Point2f>& points,
                                    const std::vector<cv::Point2f>& guesses,
                                    std::vector<cv::Point2f>& tracked) const {
  std::vector<bool> good(points.size(), false);
  tracked = guesses;
  if (points.empty()) return good;
  const cv::Size window(window_px_, window_px_);
  std::vector<unsigned char> forward_status, backward_status;
  std::vector<float> errors;
  cv::calcOpticalFlowPyrLK(previous, next, points, tracked, forward_status, errors, window, levels_,
                           criteria_, cv::OPTFLOW_USE_INITIAL_FLOW);
  // Back from where the points landed, starting at their true origin: a
  // sound track returns there in one or two iterations.
  std::vector<cv::Point2f> back = points;
  cv::calcOpticalFlowPyrLK(next, previous, tracked, back, backward_status, errors, window, levels_,
                           criteria_, cv::OPTFLOW_USE_INITIAL_FLOW);
  const cv::Size size = next.front().size();
  const float max_x = float(size.width) - 1.0f, max_y = float(size.height) - 1.0f;
  const double max_sq = forward_backward_max_px_ * forward_backward_max_px_;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!forward_status[i] || !backward_status[i]) continue;
    const cv::Point2f& p = tracked[i];
    if (!(p.x >= 0.0f && p.y >= 0.0f && p.x <= max_x && p.y <= max_y)) continue;
    const cv::Point2f d = back[i] - points[i];
    good[i] = double(d.x) * d.x + double(d.y) * d.y <= max_sq;
  }
  return good;
}

}  // namespace hsmap
