#pragma once
// KltTracker: pyramidal Lucas-Kanade optical flow (cv::calcOpticalFlowPyrLK)
// with a forward-backward check (Kalal et al., "Forward-Backward Error",
// ICPR 2010): a point is tracked from the previous image to the next and
// back, and kept only if it returns within `forward_backward_max_px` of
// where it started. This rejects the points KLT drifts on (occlusions,
// repetitive texture, the border) at the price of a second, cheap pass.
//
// Each image's pyramid is built once (buildPyramid) and used for both
// directions and, as the "previous" image, for the next frame.
//
// Starting positions: the caller passes a guess per point (the motion
// model's prediction of where a landmark projects, or the point's previous
// position); KLT starts its coarsest level there (OPTFLOW_USE_INITIAL_FLOW),
// so fast but predictable motion stays within the window.

#include <opencv2/core.hpp>
#include <vector>

#include "pipelines/frontend/frontend_options.h"

namespace hsmap {

using ImagePyramid = std::vector<cv::Mat>;

class KltTracker {
 public:
  // Sizes from `options` scaled to an image `width_px` wide.
  KltTracker(const FrontendOptions& options, int width_px);

  ImagePyramid buildPyramid(const cv::Mat& gray) const;

  // Tracks `points` of the previous image into the next one. `guesses`
  // (same size) are the starting positions in the next image. Returns the
  // tracked positions in `tracked` and, per point, whether it passed KLT, the
  // forward-backward check and stayed inside the image.
  std::vector<bool> track(const ImagePyramid& previous, const ImagePyramid& next,
                          const std::vector<cv::Point2f>& points,
                          const std::vector<cv::Point2f>& guesses,
                          std::vector<cv::Point2f>& tracked) const;

  int windowPx() const { return window_px_; }

 private:
  int window_px_;
  int levels_;
  cv::TermCriteria criteria_;
  double forward_backward_max_px_;
};

}  // namespace hsmap
