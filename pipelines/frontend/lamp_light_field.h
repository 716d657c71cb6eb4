#pragma once
// LampLightField: the light of the vehicle's lamps on the seabed as the RGB
// camera sees it, estimated from the video, so that the front-end can divide
// it out before tracking.
//
// Why: the lamps move with the camera, so their light is a brightness pattern
// fixed in the image (bright under the lamps, dim in the corners) through
// which the seabed's texture slides. KLT matches brightness in a window; a
// brightness slope that stays put while the texture moves pulls each window
// back, and the tracks fall short of the motion. The shortfall is small (on
// the simulator's `low-relief` survey, 1.4e-4 of the distance a point
// travels in the image, growing where the light falls off fastest) but it is
// the same sign for every track, so the bundle adjustment turns it into a
// scale that drifts along the track (docs/FRONTEND.md, "Lamp light").
//
// Estimate: the mean grey image of frames sampled evenly over the survey.
// The texture averages out (the frames see different ground) and the light,
// the same in every frame, remains; a Gaussian blur removes what is left of
// the texture. The field is scaled to mean 1, and floored at
// kMinRelativeLight so the darkest corners are not amplified without bound.
// A survey whose camera stays over the same ground would keep its texture in
// the mean: the blur keeps the correction to the coarse scales, which is
// also where the lamps' light varies.

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "core/survey/rgb_frame_source.h"
#include "pipelines/frontend/frontend_options.h"

namespace hsmap {

inline constexpr double kMinRelativeLight = 0.1;

// The field from 8-bit grey frames of one size: their mean, blurred by
// `blur_sigma_px`, scaled to mean 1 and floored at kMinRelativeLight.
// Throws std::invalid_argument for no frames, frames of other sizes or
// types, or a non-positive sigma.
cv::Mat lampLightFieldFromFrames(const std::vector<cv::Mat>& gray_frames, double blur_sigma_px);

// `gray` (8-bit) divided by `field` (CV_32F, same size), rounded and
// saturated to 8 bits. Throws std::invalid_argument on a size mismatch.
cv::Mat removeLampLight(const cv::Mat& gray, const cv::Mat& field);

struct LampLightEstimate {
  cv::Mat field;              // CV_32F, mean 1; empty when not estimated
  int frames_used = 0;
  int frames_skipped = 0;     // undecodable, or without usable texture
  double brightest_to_darkest = 1.0;  // of the field (after the floor)
  double seconds = 0.0;
  std::string note;           // one line for the front-end's summary
};

// Samples options.lamp_light_frames frames evenly over first..last of
// `source` (all of them when there are fewer), leaves out those that cannot
// be decoded or have no usable texture (options.min_contrast_dn,
// options.max_saturated_fraction), and estimates the field from the rest;
// with fewer than options.lamp_light_min_frames of them it gives no field
// and says why in `note`. Frames of another size than width x height are
// an error of the survey's (std::invalid_argument).
LampLightEstimate estimateLampLight(const RgbFrameSource& source, int first, int last,
                                    const FrontendOptions& options, int width_px, int height_px);

}  // namespace hsmap
