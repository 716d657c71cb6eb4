#pragma once
// Refinement of the RGB-UHI extrinsic T_C_U from the run's two ortho-images,
// after the reference paper (hyperspectral-3d-mapping-paper.tex, "extrinsic
// calibration refinement"): associations between UHI pixels and known 3D
// map points are found by matching the hyperspectral ortho-image against the
// RGB ortho-image of the mesh, and T_C_U is refined by nonlinear least
// squares so that the UHI sees those points where they are.
//
// Inputs (a run folder after the products stage, DATASET.md "Results folder"):
//   RUN/trajectory/uhi_lines.csv   T_W_U of every scan line, made with an extrinsic
//                                  T_C_U_lines: T_W_U = T_W_C(t + d) T_C_U_lines
//   RUN/hyperspectral/ortho.*      the hyperspectral ortho-image (its grid: map info)
//   RUN/hyperspectral/ancillary.*  scan line and sample of the hit nearest each pixel centre
//   RUN/map/mesh.ply               the mesh; the RGB ortho-image and its points p_W are
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
//   2. Matching. On a lattice of patch centres every patch_spacing_m, the RGB
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
//   3. Tie points. Rule: NEAREST-PIXEL ancillary. h_i = round(h) gives, from
//      the ancillary image, the scan line and sample (and range) of the UHI
//      pixel painted there; the RGB side is moved by the same rounding,
//      g' = g + (h_i - h), and its point p_W is the bilinear interpolation
//      of the renderer's points at g' (all four must be hits). The UHI pixel
//      (line, sample) thus saw p_W.
//   4. Solve (core/graph + factors + solvers, docs/ENGINE.md): one variable
//      E(0) = T_C_U, initialised at T_C_U_lines; one
//      PushbroomExtrinsicFactor per tie point with the line's camera pose
//      FIXED, T_W_C(line) = T_W_U(line) T_C_U_lines^-1, noise from the match
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
#include "pipelines/hyperspectral/ortho_grid.h"
#include "pipelines/hyperspectral/rgb_ortho.h"

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

// One association: UHI pixel (line, sample) saw the mesh point p_W.
struct ExtrinsicTiePoint {
  long long line = 0;
  double sample = 0.0;
  double range_m = 0.0;  // UHI range of the pixel (sets its noise); <= 0: 2 m
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  // Where it came from (diagnostics): RGB and hyperspectral grid positions, NCC.
  Eigen::Vector2d rgb_col_row = Eigen::Vector2d::Zero();
  Eigen::Vector2d hyper_col_row = Eigen::Vector2d::Zero();
  double ncc = 0.0;
};

// The extrinsic guess and its sigmas (survey.yaml's uhi block).
struct ExtrinsicPrior {
  SE3d T_C_U;
  double sigma_rotation_deg = 2.0;
  double sigma_translation_m = 0.05;
};

struct ExtrinsicRefinementResult {
  SE3d T_C_U_initial;  // the extrinsic of the line poses used (start of the solve)
  SE3d T_C_U;          // refined (== initial when not refined)
  bool refined = false;
  // 1-sigma: rotation about U's x, y, z (deg), translation along C's x, y, z (m);
  // nullopt when not refined or the covariance is undefined.
  std::optional<Eigen::Vector3d> sigma_rotation_deg;
  std::optional<Eigen::Vector3d> sigma_translation_m;

  // Matching.
  std::int64_t patches = 0;          // lattice patches tried
  std::int64_t matches = 0;          // kept by the NCC tests
  std::int64_t tie_points = 0;       // given (matches with ancillary and a mesh point)
  std::int64_t inliers = 0;          // tie points used in the final solve
  std::int64_t outliers = 0;         // removed after the first solve
  double median_shift_m = 0.0;       // |h - g| over the tie points, on the grid
  std::vector<double> band_weights;  // per band of the ortho (0 outside the range)
  double band_offset = 0.0;
  double band_fit_r2 = 0.0;  // of the luminance fit (0 when fixed weights)
  // Residuals over the inliers, whitened-free: RMS of u (px) and of the
  // across-line offset (as px: f * y/z), before (at T_C_U_initial) and after.
  double rms_u_before_px = 0.0, rms_across_before_px = 0.0;
  double rms_u_after_px = 0.0, rms_across_after_px = 0.0;
  std::string solve_report;  // SolveReport::toString() of the final solve
  std::vector<std::string> warnings;
  std::vector<ExtrinsicTiePoint> used;  // inlier tie points

  // A few lines for the run's log.
  std::string summary() const;
};

// Step 4 alone: refine T_C_U from tie points with the lines' camera poses.
// `line_poses` are T_W_U made with T_C_U_lines (any order; each tie point's
// line must be among them, else it is skipped with a warning). With fewer
// than options.min_tie_points usable tie points T_C_U is left at
// T_C_U_lines and the result says so (refined == false).
ExtrinsicRefinementResult refineExtrinsicFromTiePoints(
    const std::vector<ExtrinsicTiePoint>& tie_points, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera, const ExtrinsicPrior& prior,
    const ExtrinsicRefinementOptions& options = {});

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

// What the matching did with the lattice's patches.
struct OrthoMatchCounts {
  std::int64_t patches = 0;     // lattice patches
  std::int64_t textured = 0;    // both windows valid, template textured
  std::int64_t matched = 0;     // confident and unambiguous NCC peak
  std::int64_t tie_points = 0;  // of those, with ancillary and a mesh point
};

// Steps 2-3 on two luminance images of one grid: tie points from the
// ancillary image (CV_32FC4: line, sample, range, incidence; NaN empty) and
// the renderer's points. Appends to `tie_points`.
OrthoMatchCounts matchOrthoImages(const cv::Mat& rgb_luma, const cv::Mat& hyper_luma,
                                  const cv::Mat& ancillary, const RgbOrthoRenderer& renderer,
                                  const ExtrinsicRefinementOptions& options,
                                  std::vector<ExtrinsicTiePoint>& tie_points);

// Steps 1-3 on a run folder (RUN/hyperspectral/ortho.*, ancillary.*,
// RUN/map/mesh.ply): the tie points between the two ortho-images, for any
// solver that uses them (this refinement, the joint problem).
struct RunTiePoints {
  std::vector<ExtrinsicTiePoint> tie_points;
  OrthoMatchCounts counts;
  BandCombination combination;  // luma released
  double median_shift_m = 0.0;  // |h - g| over the tie points, on the grid
};
RunTiePoints collectTiePointsInRun(const std::filesystem::path& run,
                                   const UtmProjection& projection,
                                   const ExtrinsicRefinementOptions& options, std::ostream& log);

// The whole refinement on a run folder (see the header comment). T_C_U_lines
// is the extrinsic RUN/trajectory/uhi_lines.csv was made with (e.g.
// readRunCalibration(RUN/calibration.yaml).T_C_U after the products stage,
// or the previous round's result). Throws InputError / std::runtime_error for
// missing or unreadable files.
ExtrinsicRefinementResult refineExtrinsicInRun(
    const std::filesystem::path& run, const SE3d& T_C_U_lines, const PushbroomParameters& camera,
    const ExtrinsicPrior& prior, const UtmProjection& projection,
    const ExtrinsicRefinementOptions& options, std::ostream& log);

// The line poses with a new extrinsic: T_W_U' = T_W_U T_C_U_lines^-1 T_C_U_new
// (line and time kept).
std::vector<LinePose> updatedLinePoses(const std::vector<LinePose>& line_poses,
                                       const SE3d& T_C_U_lines, const SE3d& T_C_U_new);

// The grid of an ENVI header's map info (UTM, square pixels, reference pixel
// (1, 1)); std::invalid_argument otherwise.
OrthoGrid orthoGridFromHeader(const EnviHeader& header);

}  // namespace hsmap
