#pragma once
// Step 4 of the extrinsic refinement (extrinsic_refinement.h, "Method"):
// T_C_U by nonlinear least squares from tie points, the lines' camera poses
// held fixed, with the survey's guess as a prior, a robust loss, one round
// of outlier removal and the marginal covariance of the result.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/survey/pose_tables.h"
#include "pipelines/calibration/extrinsic_refinement_options.h"
#include "pipelines/calibration/extrinsic_tie_point.h"

namespace hsmap {

// The extrinsic guess and its sigmas (survey.yaml's uhi block).
struct ExtrinsicPrior {
  SE3d T_C_U;
  double sigma_rotation_deg = 2.0;
  double sigma_translation_m = 0.05;
  // 1-sigma of the time offset d the lines were posed with (survey.yaml's
  // time_offset_sigma_s). The refinement keeps d, but an error in it moves
  // every line along the trajectory, and T_C_U absorbs that: the stated
  // 1-sigma adds T_C_U's sensitivity to d times this (a "consider"
  // covariance; refineExtrinsicFromTiePoints). 0: the line times are exact.
  double time_offset_sigma_s = 0.0;
};

struct ExtrinsicRefinementResult {
  SE3d T_C_U_initial;  // the extrinsic of the line poses used (start of the solve)
  SE3d T_C_U;          // refined (== initial when not refined)
  bool refined = false;
  // 1-sigma: rotation about U's x, y, z (deg), translation along C's x, y, z (m);
  // nullopt when not refined or the covariance is undefined.
  std::optional<Eigen::Vector3d> sigma_rotation_deg;
  std::optional<Eigen::Vector3d> sigma_translation_m;
  // How T_C_U moves per second of d (rotation about U's axes in deg/s,
  // translation along C's in m/s), when prior.time_offset_sigma_s > 0; the
  // 1-sigma above includes it times that sigma.
  std::optional<Eigen::Vector3d> rotation_per_time_offset_deg_s;
  std::optional<Eigen::Vector3d> translation_per_time_offset_m_s;
  double time_offset_sigma_s = 0.0;  // prior.time_offset_sigma_s, for the summary

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
// The 1-sigma is the marginal covariance of T_C_U at the solution, plus,
// when prior.time_offset_sigma_s > 0, what the unknown error of d adds:
// the problem is solved again with every tie point's line pose taken
// +-5 ms along the lines (interpolated between them), the difference of the
// two solutions over 10 ms is T_C_U's sensitivity to d, S, and each
// component's variance becomes sigma^2 + (S sigma_d)^2.
// `line_poses` are T_W_U made with T_C_U_lines (any order; each tie point's
// line must be among them, else it is skipped with a warning). With fewer
// than options.min_tie_points usable tie points T_C_U is left at
// T_C_U_lines and the result says so (refined == false).
ExtrinsicRefinementResult refineExtrinsicFromTiePoints(
    const std::vector<ExtrinsicTiePoint>& tie_points, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera, const ExtrinsicPrior& prior,
    const ExtrinsicRefinementOptions& options = {});

}  // namespace hsmap
