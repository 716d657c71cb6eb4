#pragma once
// Exposure compensation between consecutive frames: a camera's automatic gain
// (or exposure) steps multiply every pixel of a frame by the same factor, and
// KLT (cv::calcOpticalFlowPyrLK) matches brightness: across a step of 3 dB it
// lost about 70 % of its tracks on `tiny`, and CLAHE, though it equalises
// each tile's histogram, does not undo the step (its clip limit and 8-bit
// quantisation make it only partly invariant to a gain).
//
// The relative gain r between the previous frame and the next is measured
// where both see the same seabed: for every track, the mean brightness of a
// box around its position in the previous frame and around its predicted
// position in the next (the motion model's guess, a few pixels off at most,
// which a box much larger than that hardly feels); r is the median of the
// ratios, so tracks on marine snow, on a moving shadow or off the predicted
// place do not move it. Boxes with a pixel saturated in the camera in either
// frame are left out (a clipped pixel does not scale with the gain). This is the
// affine brightness model of direct methods (Engel et al., "Direct Sparse
// Odometry", TPAMI 2018, eq. 4) without the offset: the images are
// lamp-corrected grey levels, in which a gain is a pure factor.
//
// The next frame is then brought to the previous frame's exposure (its grey
// levels divided by r) before CLAHE, and KLT tracks into that image. The
// frame's own image is kept for everything else (corners, the next frame's
// tracking), so a survey without gain changes is tracked exactly as before.

#include <opencv2/core.hpp>
#include <vector>

namespace hsmap {

struct RelativeGain {
  double ratio = 1.0;        // next / previous brightness of the same seabed
  int samples = 0;           // boxes that entered the median
  double sigma_db = 0.0;     // 1-sigma of 20 log10(ratio) (median's, from the MAD)
  double db() const;         // 20 log10(ratio)
};

// `previous`, `next`: 8-bit lamp-corrected grey images of one size;
// `previous_saturated`, `next_saturated`: their masks of pixels saturated in
// the camera (non-zero), or empty for none. `points` in `previous`, `guesses`
// where they should be in `next`. Boxes are (2 half_box_px + 1) pixels square
// and must lie inside both images; boxes darker than `min_mean_dn` are left
// out (their ratio is noise). With fewer than `min_samples` boxes the ratio
// is 1 and samples says how many there were.
RelativeGain estimateRelativeGain(const cv::Mat& previous, const cv::Mat& next,
                                  const cv::Mat& previous_saturated, const cv::Mat& next_saturated,
                                  const std::vector<cv::Point2f>& points,
                                  const std::vector<cv::Point2f>& guesses, int half_box_px,
                                  double min_mean_dn = 8.0, int min_samples = 10);

// `linear` (8-bit lamp-corrected grey) divided by `ratio`, rounded and
// clipped to 8 bits. Saturated pixels are divided too: their level is the
// least the pixel can be, and the previous frame shows its own saturated
// pixels at that level of its exposure.
cv::Mat compensateGain(const cv::Mat& linear, double ratio);

}  // namespace hsmap
