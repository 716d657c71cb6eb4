#pragma once
// The options of the extrinsic refinement (extrinsic_refinement.h, "Method"),
// one group per step; every step of the refinement takes the whole struct.

namespace hsmap {

struct ExtrinsicRefinementOptions {
  // Luminance (step 1).
  double band_min_nm = 450.0;
  double band_max_nm = 650.0;
  bool fit_band_weights = true;
  double ridge = 1e-3;    // relative to the mean diagonal of the normal equations
  int fit_stride_px = 4;  // fit on every n-th row and column
  // Matching (step 2).
  double patch_spacing_m = 0.15;
  double patch_size_m = 0.20;
  double search_radius_m = 0.15;
  // Coarse step before the lattice (a bad guess of T_C_U or d shifts the
  // whole hyperspectral ortho-image by more than search_radius_m): patches of
  // coarse_patch_size_m every coarse_spacing_m, on images resampled to
  // coarse_pixel_m, searched within +-coarse_search_radius_m; each lattice
  // patch is then searched around the median shift of the coarse matches
  // within coarse_neighbourhood_m. coarse_pixel_m = 0: no coarse step.
  double coarse_pixel_m = 0.01;
  double coarse_patch_size_m = 0.4;
  double coarse_spacing_m = 0.2;
  double coarse_search_radius_m = 0.4;
  double coarse_neighbourhood_m = 0.6;
  int coarse_min_matches = 3;  // around a patch; fewer: searched around no shift
  double blur_sigma_px = 1.5;
  double highpass_sigma_px = 10.0;  // minus a blur of this sigma (shading); 0: off
  double min_ncc = 0.7;
  double min_peak_margin = 0.1;
  double exclusion_radius_px = 6.0;
  double min_template_std = 0.25;  // of the image's standard deviation
  // Solve (step 4).
  double sigma_match_m = 0.005;  // 1-sigma of a match on the ground
  double robust_scale = 3.0;     // Cauchy, in sigmas
  int min_tie_points = 6;        // fewer: the prior alone (T_C_U kept)
  int max_iterations = 50;
  int num_threads = 0;  // 0: every hardware thread

  // std::invalid_argument naming the field and what is allowed.
  void validate() const;
};

}  // namespace hsmap
