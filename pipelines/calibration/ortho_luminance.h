#pragma once
// Step 1 of the extrinsic refinement (extrinsic_refinement.h, "Method"): the
// luminance images of the RGB and the hyperspectral ortho-image on their
// common grid, which the matching (ortho_matching.h) compares. The
// hyperspectral one is the band combination closest to the RGB camera's
// response; see extrinsic_refinement.h for how and why it is fitted.

#include <opencv2/core.hpp>
#include <vector>

#include "core/io/envi_reader.h"
#include "pipelines/calibration/extrinsic_refinement_options.h"

namespace hsmap {

// Step 1: the hyperspectral luminance (CV_32F, NaN where empty) and how it
// was made.
struct BandCombination {
  cv::Mat luma;                 // CV_32F, rows x cols
  std::vector<double> weights;  // per band
  double offset = 0.0;
  double r2 = 0.0;
  bool fitted = false;
};

// Step 1 on an open ortho-image (rows x cols x bands, one wavelength per
// band): bands in [band_min_nm, band_max_nm] averaged in bins of 20 nm, the
// bins' weights fitted to `rgb_luma` (or fixed, see the header comment).
// One pass over the file. std::invalid_argument when no band is in range or
// the sizes differ.
BandCombination hyperspectralLuminance(const EnviReader& ortho,
                                       const std::vector<double>& wavelengths_nm,
                                       const cv::Mat& rgb_luma,
                                       const ExtrinsicRefinementOptions& options);

// The RGB luminance (CV_32F, NaN where alpha is 0) of a BGRA image.
cv::Mat rgbLuminance(const cv::Mat& bgra);

}  // namespace hsmap
