#pragma once
// The ortho-image metrics of metrics.json (DATASET.md, "Ortho-image"): the
// produced hyperspectral ortho-image RUN/hyperspectral/ortho.hdr against the
// true reflectance ortho-image truth/reflectance.hdr.
//
// Inputs
//   produced  ENVI, north-up in UTM (`map info = {UTM, 1, 1, easting,
//             northing, px, px, zone, North|South, WGS-84, units=Meters}`, the
//             zone of the survey origin); empty pixels are NaN or the header's
//             `data ignore value`.
//   truth     ENVI float32, north-up in local W (`map info = {Arbitrary, 1, 1,
//             E, N, px, px, units=Meters}`), NaN outside the swath.
// Pixel centres follow ENVI's reference pixel (1-based corner, as in
// true_surface_samples.h): row r, column c is at
//   x = X + (c + 1.5 - x_ref) px_x,   y = Y - (r + 1.5 - y_ref) px_y.
// A pixel is valid when any of its bands is a number (and, in the produced
// raster, not the data ignore value).
//
// Everything is measured on the TRUTH's grid: for a truth pixel centre
// p_W = (north, east, reference_down_m) the produced raster is sampled at
// UtmProjection::nedToUtm(p_W) (the W -> UTM map through the survey origin,
// meridian convergence and point scale included). That map is evaluated
// exactly every 16 truth pixels and interpolated bilinearly in between (its
// curvature over 16 pixels is ~1e-9 m). Displacements therefore come out in
// W's north and east, in metres.
//
// Registration (ortho_mean_shift_m, ortho_registration_rmse_m, ortho_scale_error)
//   1. Single-band images: the mean over the valid bands of every pixel, for
//      the truth on its grid and for the produced raster on its own grid
//      (streamed line by line: the cubes are never loaded). The produced mean
//      is resampled onto the truth grid BILINEARLY (NaN when any of the four
//      neighbours is empty).
//   2. Coarse similarity, then coarse shift. A patch's correlation finds a
//      displacement up to half a patch, of content that is the same up to a
//      shift; a map scale error s breaks both far from the scale's centre
//      (at 11 % over a 4 m swath, ~0.2 m and a 3 cm stretch inside each
//      0.3 m patch: 6 of 37 patches matched). So first a 2-D similarity S0
//      (W's (east, north): a -> A_W a + b_W) between the truth image and the
//      produced one resampled as placed is found by feature matching
//      (ortho_coarse_similarity.h: SIFT on images reduced to at most 1024
//      pixels a side, RANSAC; why not log-polar phase correlation is said
//      there), and every patch looks the produced raster up at S0(a) instead
//      of a: what is left to each patch is the map's local error. Then the
//      truth and the produced image so warped (or as placed, when S0 was not
//      found or use_coarse_similarity is off), normalised and reduced to at
//      most coarse_max_side pixels a side (area averaging), are
//      phase-correlated whole; a confident result (response >=
//      coarse_min_response) is the starting displacement of every patch, so
//      that a geo-referencing error larger than half a patch (decimetres from
//      the INS) is still measured. Measured on rugged (sequential, ~0.8 %
//      scale error) the figures are those of the shift alone within the
//      patches' noise; with the product's map info scaled by 1.11 about its
//      centre, 403 of 494 patches match (45 without S0: null) and
//      ortho_scale_error is 0.1013 (expected 1.11 x 0.9924 = 1.1016).
//   3. Patches: the truth raster is tiled by squares of
//      max(min_patch_pixels, round(patch_size_m / px)) pixels (0.3 m: 60
//      pixels at 5 mm), centred on the raster. A patch HAS DATA when at least
//      min_valid_fraction of its pixels are valid in the truth and in the
//      resampled produced image. Each image patch is normalised (mean 0, unit
//      standard deviation over its valid pixels; empty pixels set to 0) and
//      phase-correlated with a Hanning window, the whitened cross-power
//      spectrum weighted by a low-pass of correlation_cutoff_m (4 cm;
//      band_limited_phase_correlation.h says why: with plain phase
//      correlation, an ortho-image cast from the true poses onto the true
//      rugged surface scored 9.9 mm, the speckle of the truth raster's finest
//      texture; band-limited, 4.2 mm with 445 instead of 196 of 503 patches
//      matched). Its peak estimator (the
//      centroid of a 5 x 5 window) is biased towards whole pixels by up to
//      ~0.3 pixel, so the produced patch is resampled again at the current
//      displacement and correlated again until the correction is below
//      refinement_tolerance_px (at most max_refinements times): near a zero
//      residual shift the estimator is unbiased. The estimates after the
//      first correction wander about the displacement by the estimator's
//      noise (~0.2 pixel, below) rather than settle, so the patch's
//      displacement is their mean (which halves the noise floor).
//      A patch MATCHES when its last correlation's response (the share of the
//      correlation energy in the 5 x 5 window around the peak, in [0, 1]) is
//      >= min_response (0.3: the same texture sampled on the two grids gives
//      ~0.6-1, unrelated textures and a featureless image <= ~0.2), the last
//      correction is <= 0.5 pixel, and neither patch is featureless.
//      A match is then CONFIRMED on a second window of the same size shifted
//      diagonally by a quarter of the patch (the first of the four diagonal
//      directions that stays inside the raster and has data): it must match
//      too, with a displacement within confirmation_tolerance_m (and 2
//      pixels) of the first. A real displacement of the map is the same over
//      the 56 % the two windows share; a spurious peak of the correlation
//      (weak or repetitive texture) moves with the window. On rugged, two
//      such peaks of 96 and 127 mm among 417 patches (responses 0.39 and
//      0.49) had lifted the RMS from 5 to 9 mm. Unconfirmed matches are
//      counted apart (patches_unconfirmed) and do not count as matched.
//      Noise floor (tests/pipelines/evaluate/ortho_metrics_test.cc: smooth
//      texture, truth at 5 mm in W, product at 4 mm in UTM): one
//      correlation's estimate scatters by ~0.2 pixel, because phase
//      correlation's whitening gives the weak high frequencies, where the two
//      grids' interpolation differs, as much weight as the strong ones; after
//      the averaging above, ortho_registration_rmse_m of an exact product is
//      0.5-0.6 mm (~0.1 pixel), and the mean shift and the scale, averages
//      over the patches, come out within ~0.3 mm and ~3e-4 of the truth.
//   4. A match's displacement d is where the patch's content lies in the
//      produced map minus where it lies in the truth (north, east; m): with
//      d_w the displacement the patch measured on the warped image (its
//      pixels times the truth's pixel size), b = S0(a + d_w) and d = b - a;
//      composing back with S0 makes the figures below those of the produced
//      image against the truth, whatever S0 took out (identity without S0).
//      ortho_mean_shift_m = |mean d|. A 2-D similarity b = s R a + t is fitted
//      by linear least squares to (a = patch centre, b = a + d) (exact: it is
//      linear in (s cos th, s sin th, t)); ortho_registration_rmse_m =
//      sqrt(mean |b - S a|^2), ortho_scale_error = |s - 1|. With fewer than
//      min_matched_fraction (30 %) of the patches with data matched, or fewer
//      than min_matched_patches (3), the three are missing with the counts.
//
// Spectra (ortho_coverage, ortho_sam_deg)
//   ortho_coverage  fraction of the truth's valid pixels (all of them) whose
//                   centre falls in a valid produced pixel (NEAREST pixel), the
//                   produced raster taken at the REGISTERED position S(a) when
//                   the registration was measured, else as placed: like
//                   mesh_completeness (after the frames' alignment), it judges
//                   what the product covers, not where the INS put it (on
//                   rugged an 18 cm INS shift alone cost 0.09 of coverage
//                   as placed); coverage_registered says which, and
//                   covered_pixels_as_placed keeps the other count.
//   ortho_sam_deg   mean over covered pixels of the spectral angle
//                   acos(<p, t> / (|p| |t|)) (computed as 2 asin(|p^ - t^| / 2),
//                   well conditioned near 0), in degrees, between the true
//                   spectrum t and the produced spectrum p of the NEAREST
//                   produced pixel (no mixing of neighbours' spectra). The
//                   produced pixel is taken at the REGISTERED position S(a)
//                   when the registration was measured (so that SAM judges
//                   the spectra, not the geo-referencing error already
//                   reported by the three metrics above), else as placed;
//                   OrthoMetrics::sam_registered says which. Pixels with a
//                   non-finite band or a zero spectrum are left out. Only the
//                   lattice of every sam_stride-th row and column is measured
//                   (footprintStride with max_sam_pixels, as mesh_completeness):
//                   the truth's lattice rows are read in chunks and the
//                   produced lines they need streamed in order, so memory
//                   stays at ~sam_chunk_bytes. Missing when the two rasters
//                   have different band counts.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/geodetic_point.h"
#include "pipelines/evaluate/metric_value.h"
#include "pipelines/evaluate/ortho_coarse_similarity.h"

namespace hsmap {

struct OrthoMetricsOptions {
  // Side of the registration patches (DATASET.md: about 0.3 m), and its floor
  // in pixels for coarse rasters (phase correlation needs some pixels).
  double patch_size_m = 0.3;
  int min_patch_pixels = 16;
  // A patch has data when this fraction of its pixels is valid in both images.
  double min_valid_fraction = 0.9;
  // Confidence of a patch's phase correlation (cv::phaseCorrelate's response).
  double min_response = 0.3;
  // A match must be found again, within this (and 2 pixels), on a window
  // shifted by a quarter patch; false: every match is taken as it is.
  bool confirm_matches = true;
  double confirmation_tolerance_m = 0.01;
  // Sub-pixel refinement: re-correlate until the correction is below this.
  int max_refinements = 6;
  double refinement_tolerance_px = 0.02;
  // Coarse similarity (ortho_coarse_similarity.h) the patches are matched
  // through; false: a whole-image shift only (a map scale error of a few
  // per cent then leaves the far patches unmatched).
  bool use_coarse_similarity = true;
  CoarseSimilarityOptions coarse_similarity;
  // Coarse whole-image correlation (starting shift of every patch, after the
  // coarse similarity when there is one).
  int coarse_max_side = 512;
  double coarse_min_response = 0.1;
  // DATASET.md: null when fewer than 30 % of the patches with data, or fewer
  // than 3, match.
  double min_matched_fraction = 0.3;
  int min_matched_patches = 3;
  // Bound on the pixels of the spectral-angle lattice, and on the memory of
  // the truth spectra held at once while measuring it.
  std::int64_t max_sam_pixels = 200000;
  std::int64_t sam_chunk_bytes = 64LL << 20;
  // Down coordinate (W) of the truth pixel centres projected to UTM; the
  // effect of a wrong value is |p| d / R (30 um at 20 m for 10 m).
  double reference_down_m = 0.0;
  // Band limit of the patch correlations (band_limited_phase_correlation.h):
  // wavelengths shorter than this weigh less (e^-1/2 at this wavelength).
  // 4 cm is about three scan-line spacings of a push-broom survey at
  // 0.4 m/s and 30 lines/s: finer texture is sampled differently by the
  // product and by the truth raster. 0: plain phase correlation.
  double correlation_cutoff_m = 0.04;

  // std::invalid_argument naming the field when a value is out of range.
  void validate() const;
};

// One matched patch.
struct OrthoPatchMatch {
  Eigen::Vector2d centre_NE = Eigen::Vector2d::Zero();        // patch centre in W (north, east), m
  Eigen::Vector2d displacement_NE = Eigen::Vector2d::Zero();  // produced minus true position, m
  double response = 0.0;                                      // of the last correlation
};

struct OrthoMetrics {
  MetricValue ortho_mean_shift_m;
  MetricValue ortho_registration_rmse_m;
  MetricValue ortho_scale_error;
  MetricValue ortho_sam_deg;
  MetricValue ortho_coverage;

  int patch_pixels = 0;       // side of a patch in truth pixels
  int patches = 0;            // patches tiling the truth raster
  int patches_with_data = 0;  // of those, with enough valid pixels in both
  int patches_matched = 0;    // of those, confidently matched (and confirmed)
  int patches_unconfirmed = 0;  // matched, but not found again on the shifted window
  std::vector<OrthoPatchMatch> matches;
  // The coarse stage's displacement at the truth raster's centre (north,
  // east; m), when it found one (similarity or shift).
  std::optional<Eigen::Vector2d> coarse_shift_NE;
  // The coarse similarity (W to the produced map), when found: its scale,
  // rotation (degrees, as rotation_deg), and the feature matches passing the
  // ratio test and the RANSAC inliers among them.
  std::optional<double> coarse_scale;
  std::optional<double> coarse_rotation_deg;
  int coarse_feature_matches = 0;
  int coarse_feature_inliers = 0;
  // The fitted similarity's rotation (degrees, anticlockwise seen from above
  // in (east, north)) when the registration was measured.
  std::optional<double> rotation_deg;

  std::int64_t footprint_pixels = 0;  // valid truth pixels
  std::int64_t covered_pixels = 0;    // of those, over a valid produced pixel
  bool coverage_registered = false;   // covered_pixels counted at the registered position
  std::int64_t covered_pixels_as_placed = 0;  // when coverage_registered: the count as placed
  int sam_stride = 1;                 // lattice stride of the spectral angle
  std::int64_t sam_pixels = 0;        // pixels the spectral angle is the mean of
  bool sam_registered = false;        // spectra compared at the registered position

  // A few lines for people: the five figures (or their reasons) and the counts.
  std::string summary() const;
};

// Measures `produced_hdr` against `truth_hdr`, with `origin` the survey
// origin (W's origin; UTM zone). Throws InputError naming the header for a
// truth raster whose map info is missing, not `Arbitrary` or has non-positive
// pixel sizes, a produced raster whose map info is missing, not UTM, or in
// another zone or hemisphere than the origin's, an unreadable `data ignore
// value`, and what EnviReader throws for a bad raster;
// std::invalid_argument for bad options or origin.
OrthoMetrics measureOrtho(const std::filesystem::path& produced_hdr,
                          const std::filesystem::path& truth_hdr, const GeodeticPoint& origin,
                          const OrthoMetricsOptions& options = {});

// Why the five metrics are missing when the run wrote no ortho-image.
inline constexpr const char* kNoOrthoImage =
    "RUN/hyperspectral/ortho.hdr not found: the run has no products stage";

// On a run's files (evaluate): measureOrtho(produced_hdr, truth_hdr, origin)
// when produced_hdr (RUN/hyperspectral/ortho.hdr) exists; otherwise the five
// metrics are missing with kNoOrthoImage and nothing is read. Throws
// InputError naming truth_hdr (SURVEY/truth/reflectance.hdr) when the
// ortho-image exists but the true one does not, and what measureOrtho throws.
OrthoMetrics measureRunOrtho(const std::filesystem::path& produced_hdr,
                             const std::filesystem::path& truth_hdr, const GeodeticPoint& origin,
                             const OrthoMetricsOptions& options = {});

}  // namespace hsmap
