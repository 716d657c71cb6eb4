#pragma once
// The pieces of NCC matching between the RGB and the hyperspectral
// luminance ortho-images that the coarse step (coarse_ortho_shift.h) and the
// lattice (ortho_matching.h) share: the band-passed image with its mask, and
// the confident, unambiguous peak of a score map.

#include <optional>
#include <opencv2/core.hpp>

namespace hsmap {

// A luminance image band-passed for matching: NaN replaced by the mean of
// the valid pixels, blurred by blur_sigma_px, minus a blur of
// highpass_sigma_px (0: none); `valid` is 255 where the original was finite.
struct PreparedImage {
  cv::Mat blurred;  // CV_32F
  cv::Mat valid;    // CV_8U
  double stddev = 0.0;  // of `blurred` over the valid pixels
};

PreparedImage prepareForMatching(const cv::Mat& luma, double blur_sigma_px,
                                 double highpass_sigma_px);
// The same with a sigma per axis (x: columns, y: rows), for images whose
// pixels are not square on the ground (a push-broom strip: lines x samples).
PreparedImage prepareForMatching(const cv::Mat& luma, cv::Point2d blur_sigma_px,
                                 cv::Point2d highpass_sigma_px);

// The same image resampled to 1/factor of its size (area average); a
// coarse pixel is valid only when every fine pixel under it is.
PreparedImage downsampled(const PreparedImage& image, int factor);

bool allValid(const cv::Mat& valid, const cv::Rect& window);

// The best peak of a TM_CCOEFF_NORMED score map, refined to sub-pixel by a
// parabola in each axis, when it is confident (>= min_ncc), not on the map's
// border, and unambiguous (every score farther than exclusion_radius_px from
// it below best - min_peak_margin).
struct NccPeak {
  double x = 0.0, y = 0.0;  // in the score map, sub-pixel
  double ncc = 0.0;
};
std::optional<NccPeak> unambiguousPeak(const cv::Mat& scores, double min_ncc,
                                       double min_peak_margin, double exclusion_radius_px);
// The same with an elliptic exclusion zone (radius per axis, in pixels).
std::optional<NccPeak> unambiguousPeak(const cv::Mat& scores, double min_ncc,
                                       double min_peak_margin, cv::Point2d exclusion_radius_px);

}  // namespace hsmap
