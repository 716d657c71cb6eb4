#pragma once
// Refinement of the RGB-UHI extrinsic T_C_U from the run's two ortho-images,
// after the reference paper (hyperspectral-3d-mapping-paper.tex, "extrinsic
// calibration refinement"): associations between UHI pixels and known 3D
// map points are found by matching the hyperspectral ortho-image against the
// RGB ortho-image of the mesh, and T_C_U is refined by nonlinear least
// squares so that the UHI sees those points where they are.
//
// Inputs (the refine stage's, docs/RUN.md):
//   line poses                     T_W_U of every scan line, made with an extrinsic
//                                  T_C_U_lines: T_W_U = T_W_C(t + d) T_C_U_lines
//   ORTHO/ortho.*                  a cast of those lines onto the mesh (product_casting.h):
//                                  the hyperspectral ortho-image (its grid: map info)
//   ORTHO/ancillary.*              scan line and sample of the hit nearest each pixel centre
//                                  (a gap-filled pixel's interpolated)
//   the mesh                       the RGB ortho-image and its points p_W are
//                                  rendered from it on the same grid (RgbOrthoRenderer)
//
// Method
//   1. Luminance images on the ortho grid. RGB: Y = 0.299 R + 0.587 G + 0.114 B.
//      Hyperspectral: a weighted sum of the bands in [band_min_nm, band_max_nm],
//      the weights fitted by ridge least squares (plus an offset) to the RGB
//      luminance on a subsample of pixels valid in both (fit_band_weights), or
//      fixed luminance-like weights (blue 450-500, green 500-570, red 570-650
//      nm, 0.114 / 0.587 / 0.299 shared over each range's bands). The fit
//      finds "the band combination closest to the RGB camera's response";
//      the images are not yet aligned when it runs, so it is done on blurred
//      images, and NCC makes the matching indifferent to gain and offset.
//   2. Matching, coarse to fine. Coarse step (coarse_ortho_shift.h): both
//      images resampled to coarse_pixel_m, large patches
//      (coarse_patch_size_m) every coarse_spacing_m searched within
//      +-coarse_search_radius_m with the tests below; a lattice patch's
//      search is centred on the per-axis median shift of the coarse matches
//      within coarse_neighbourhood_m (no shift with fewer than
//      coarse_min_matches there), so a guess that moves the hyperspectral
//      image by more than search_radius_m is still matched.
//      Lattice: patch centres every patch_spacing_m, the RGB
//      luminance patch (patch_size_m square) is the template; it is searched
//      in the hyperspectral luminance within +-search_radius_m by normalised
//      cross-correlation (cv::matchTemplate, TM_CCOEFF_NORMED) after a
//      band-pass (a Gaussian blur of blur_sigma_px, minus a blur of
//      highpass_sigma_px that removes the lights' shading, which differs
//      between the two cameras). A match is kept when
//        - both windows are fully valid (no empty pixels) and textured
//          (template standard deviation >= min_template_std of the image's),
//        - the best NCC >= min_ncc, not on the search window's border,
//        - unambiguous: the best NCC outside a disc of exclusion_radius_px
//          around the peak is below best - min_peak_margin,
//      and the peak is refined to sub-pixel by a parabola in each axis.
//      A match says: the content at RGB grid position g shows up in the
//      hyperspectral ortho at h = g + shift.
//   3. Tie points. Rule: the ancillary image INTERPOLATED at h (bilinear
//      over the four pixels around it, which must all be set and span at
//      most 4 lines) gives the UHI pixel's continuous line position and
//      sample; p_W is the renderer's point at g. Otherwise the nearest
//      pixel h_i = round(h), the RGB side moved by the same rounding,
//      g' = g + (h_i - h). p_W is the bilinear interpolation of the
//      renderer's points (all four must be hits). The UHI pixel
//      (line position, sample) thus saw p_W.
//   4. Solve (core/graph + factors + solvers, docs/ENGINE.md): one variable
//      E(0) = T_C_U, initialised at T_C_U_lines; one
//      PushbroomExtrinsicFactor per tie point with the line's camera pose
//      FIXED, T_W_C = T_W_U T_C_U_lines^-1 with T_W_U interpolated between
//      the two lines around the line position, noise from the match
//      precision on the ground (sigma_match_m) over the pixel's range
//      (sigma_u = f sigma_match_m / range, sigma_across = sigma_match_m /
//      range), a Cauchy loss of scale robust_scale; an ExtrinsicPriorFactor
//      on E(0) at survey.yaml's guess with its sigmas (the prior is always
//      the survey's, never a previous round's estimate, so rounds do not
//      count it twice). After a first solve the factors beyond the loss
//      scale are outliers: removed, and the problem solved again; the
//      marginal covariance of E(0) (solvers/marginal_covariance.h) gives
//      the 1-sigma of rotation about U's axes (deg) and of translation
//      along C's axes (m; the right perturbation's rho is in U, rotated
//      into C: Sigma_t = R_C_U Sigma_rho R_C_U^T).
//
// Not estimated: the time offset d and the trajectory (line poses are fixed);
// a time offset error shows up as an apparent shift along track and is
// partly absorbed by T_C_U. Iterating (recast with updatedLinePoses(),
// refine again) converges as the ortho-images come into register.
//
// Where each part lives (this header includes them all):
//   extrinsic_refinement_options.h  the options of every step
//   ortho_luminance.h               step 1
//   ortho_matching.h                steps 2-3 on two luminance images
//   extrinsic_tie_point.h           a tie point (what steps 2-3 make)
//   run_tie_points.h                steps 1-3 on a cast
//   extrinsic_from_tie_points.h     step 4, the prior and the result
//   ortho_grid_from_header.h        an ortho-image's grid from its header
//   this header                     the whole refinement on a cast

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/geometry/utm_projection.h"
#include "core/io/envi_header.h"
#include "core/io/envi_reader.h"
#include "core/survey/pose_tables.h"
#include "pipelines/calibration/extrinsic_from_tie_points.h"
#include "pipelines/calibration/extrinsic_refinement_options.h"
#include "pipelines/calibration/extrinsic_tie_point.h"
#include "pipelines/products/ortho_grid.h"
#include "pipelines/products/ortho_grid_from_header.h"
#include "pipelines/calibration/ortho_luminance.h"
#include "pipelines/calibration/ortho_matching.h"
#include "pipelines/products/rgb_ortho.h"
#include "pipelines/calibration/run_tie_points.h"

namespace hsmap {

// The whole refinement on a cast (see the header comment): `ortho_folder`
// holds the cast of `line_poses` onto `mesh`; T_C_U_lines is the extrinsic
// the line poses were made with (the geo-referencing's, or the previous
// round's result). Throws InputError / std::runtime_error for missing or
// unreadable files.
ExtrinsicRefinementResult refineExtrinsicFromOrthoImages(
    const std::filesystem::path& ortho_folder, const PlyMesh& mesh, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera, const ExtrinsicPrior& prior,
    const UtmProjection& projection, const ExtrinsicRefinementOptions& options, std::ostream& log);

// The line poses with a new extrinsic: T_W_U' = T_W_U T_C_U_lines^-1 T_C_U_new
// (line and time kept).
std::vector<LinePose> updatedLinePoses(const std::vector<LinePose>& line_poses,
                                       const SE3d& T_C_U_lines, const SE3d& T_C_U_new);

}  // namespace hsmap
