#include "pipelines/calibration/extrinsic_refinement_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace hsmap {

namespace {

void require(bool ok, const std::string& field, const std::string& expectation, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "ExtrinsicRefinementOptions: " << field << " must be " << expectation << ", got "
          << value;
  throw std::invalid_argument(message.str());
}

}  // namespace

void ExtrinsicRefinementOptions::validate() const {
  require(std::isfinite(band_min_nm) && std::isfinite(band_max_nm) && band_max_nm > band_min_nm,
          "band_max_nm", "above band_min_nm", band_max_nm);
  require(std::isfinite(ridge) && ridge >= 0.0, "ridge", ">= 0", ridge);
  require(fit_stride_px >= 1, "fit_stride_px", ">= 1", fit_stride_px);
  require(std::isfinite(patch_spacing_m) && patch_spacing_m > 0.0, "patch_spacing_m", "> 0",
          patch_spacing_m);
  require(std::isfinite(patch_size_m) && patch_size_m > 0.0, "patch_size_m", "> 0", patch_size_m);
  require(std::isfinite(search_radius_m) && search_radius_m > 0.0, "search_radius_m", "> 0",
          search_radius_m);
  require(std::isfinite(coarse_pixel_m) && coarse_pixel_m >= 0.0, "coarse_pixel_m", ">= 0",
          coarse_pixel_m);
  if (coarse_pixel_m > 0.0) {
    require(std::isfinite(coarse_patch_size_m) && coarse_patch_size_m > 0.0, "coarse_patch_size_m",
            "> 0", coarse_patch_size_m);
    require(std::isfinite(coarse_spacing_m) && coarse_spacing_m > 0.0, "coarse_spacing_m", "> 0",
            coarse_spacing_m);
    require(std::isfinite(coarse_search_radius_m) && coarse_search_radius_m > 0.0,
            "coarse_search_radius_m", "> 0", coarse_search_radius_m);
    require(std::isfinite(coarse_neighbourhood_m) && coarse_neighbourhood_m > 0.0,
            "coarse_neighbourhood_m", "> 0", coarse_neighbourhood_m);
    require(coarse_min_matches >= 1, "coarse_min_matches", ">= 1", coarse_min_matches);
  }
  require(std::isfinite(blur_sigma_px) && blur_sigma_px >= 0.0, "blur_sigma_px", ">= 0",
          blur_sigma_px);
  require(std::isfinite(highpass_sigma_px) && highpass_sigma_px >= 0.0, "highpass_sigma_px", ">= 0",
          highpass_sigma_px);
  require(min_ncc > -1.0 && min_ncc <= 1.0, "min_ncc", "in (-1, 1]", min_ncc);
  require(min_peak_margin >= 0.0 && min_peak_margin < 2.0, "min_peak_margin", "in [0, 2)",
          min_peak_margin);
  require(exclusion_radius_px >= 1.0, "exclusion_radius_px", ">= 1", exclusion_radius_px);
  require(min_template_std >= 0.0, "min_template_std", ">= 0", min_template_std);
  require(std::isfinite(sigma_match_m) && sigma_match_m > 0.0, "sigma_match_m", "> 0",
          sigma_match_m);
  require(std::isfinite(robust_scale) && robust_scale > 0.0, "robust_scale", "> 0", robust_scale);
  require(min_tie_points >= 1, "min_tie_points", ">= 1", min_tie_points);
  require(max_iterations >= 1, "max_iterations", ">= 1", max_iterations);
  require(num_threads >= 0, "num_threads", ">= 0", num_threads);
}

}  // namespace hsmap
