#pragma once
// ImagePreprocessor: an RGB frame (8-bit BGR, as RgbFrameSource decodes it)
// turned into the 8-bit grey image that the tracker works on, and the
// measures that say whether the frame has usable texture at all.
//
// Grey: OpenCV's luma (cv::COLOR_BGR2GRAY). Then, when a lamp light field is
// given, the frame divided by it (lamp_light_field.h). Then, when enabled, CLAHE
// (contrast-limited adaptive histogram equalisation, Zuiderveld 1994): the
// lamps of an ROV light the seabed unevenly and dimly, so a global contrast
// leaves the image corners nearly black; CLAHE equalises contrast per tile
// with a clip limit that stops it from amplifying the sensor noise of flat
// regions into false corners. The quality measures are taken on the grey
// image *before* CLAHE, which would stretch a black frame's noise into
// apparent texture.
//
// Not thread-safe (the CLAHE object keeps buffers): one per thread.

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "pipelines/frontend/frontend_options.h"

namespace hsmap {

struct ImageQuality {
  double mean_dn = 0.0;             // mean grey level, 8-bit DN
  double contrast_dn = 0.0;         // standard deviation of the grey levels
  double saturated_fraction = 0.0;  // pixels at >= 250 DN
};

class ImagePreprocessor {
 public:
  // `width_px`: the survey's image width, for the CLAHE tile size.
  // `lamp_light_field`: CV_32F of the image's size (estimateLampLight), or
  // empty for none.
  ImagePreprocessor(const FrontendOptions& options, int width_px, int height_px,
                    cv::Mat lamp_light_field = {});

  // Grey image to track on (CLAHE applied when enabled); `quality`, when not
  // null, receives the measures of the raw grey image; `linear`, when not
  // null, the grey image before CLAHE (lamp light removed), in which a gain
  // step is a pure factor (exposure_compensation.h); `saturated`, when not
  // null, the mask (255) of its pixels saturated in the camera (>= 250 DN,
  // as ImageQuality counts them).
  cv::Mat process(const cv::Mat& bgr, ImageQuality* quality, cv::Mat* linear = nullptr,
                  cv::Mat* saturated = nullptr) const;

  // CLAHE of a `linear` image when enabled, else the image itself: the last
  // step of process().
  cv::Mat equalise(const cv::Mat& linear) const;

  // The 8-bit grey image of an 8-bit BGR (or already grey) frame, before
  // any correction; throws std::invalid_argument for other channel counts.
  static cv::Mat grey(const cv::Mat& bgr);

  // Measures of an 8-bit grey image (on a 4x subsampled copy: statistics, not detail).
  static ImageQuality measure(const cv::Mat& gray);

 private:
  bool use_clahe_;
  cv::Mat lamp_light_field_;
  cv::Ptr<cv::CLAHE> clahe_;
};

}  // namespace hsmap
