#pragma once
// The global joint problem (the `joint` variant, docs/JOINT.md): one sparse
// least-squares problem over
//   S(j)  the control points of the camera trajectory spline T_W_C(t)
//         (joint_spline.h),
//   L(l)  the landmarks of the geo-referenced sparse map (p_W),
//   E(0)  the RGB-UHI extrinsic T_C_U,
//   D(0)  the UHI time offset d (true line time = recorded + d),
//   K(0)  the UHI intrinsics [f cx k1 k2], only when some of
//         JointInputs::uhi_intrinsics_sigma is > 0 (self-calibration,
//         issue 44): shared by every tie point, with a prior at uhi_camera
//         (PushbroomIntrinsicsPriorFactor); a sigma of 0 holds its parameter,
// with the factors
//   - every posed frame's observations of the landmarks
//     (SplineReprojectionFactor at the frame's time; Huber loss): the
//     front-end tracked them in every frame, not only in keyframes, so the
//     spline is determined between keyframes by the video itself. A
//     keyframe's observations are the map's (the keyframe adjustment's set,
//     with each track's sighting at its detection); the other frames' are
//     weighted `other_frame_sigma_factor` times less in sigma, because a
//     track's pixels in consecutive frames share its accumulated KLT drift
//     and its early life (detection to triangulation) is missing from them
//     (docs/JOINT.md, "Weights");
//   - every INS fix on the spline at its own time (SplineInsPositionFactor,
//     SplineInsAttitudeFactor) with the noise of the geo-referencing stage
//     (survey.yaml's sigmas, positions inflated by the INS's correlation
//     time); fixes the geo-referencing left out stay out;
//   - every cross-modal tie point (a UHI pixel of a scan line that saw a
//     known point of the surface) through the spline at the line's recorded
//     time + d, T_C_U and d (Cauchy loss): a PushbroomCameraPointFactor, the
//     point carried by the trajectory from where the RGB camera was at the
//     line's time (see JointInputs::surface_trajectory);
//   - the survey's priors on T_C_U and d (ExtrinsicPriorFactor,
//     TimeOffsetPriorFactor);
//   - spline smoothness only where the data are thin: around a control
//     point whose support (the four segments it moves) holds fewer than
//     `min_frames_in_support` posed frames or less than one frame's worth
//     of their basis weight (the end of the spline past the last frame).
// Weights: pixels at pixel_sigma_px; tie points at sigma_match_m on the
// ground over the pixel's range; INS and priors as the survey states them;
// smoothness as a prior on the vehicle's accelerations (docs/JOINT.md).
//
// The solve runs twice: the tie points beyond their loss scale after the
// first are removed (outliers), then the problem is solved again from the
// first's estimate. d is bounded to the tie factors' window around its
// start; when it ends at the bound, the problem is built again around the
// new d and solved from the result (JointOptions::max_rewindows). The 1-sigma of T_C_U and d comes from their joint
// marginal covariance (solvers/marginal_covariance.h) with every other
// variable free; a component whose 1-sigma is more than
// `weak_fraction_of_prior` of the prior's is reported as weakly determined
// by the survey (the data hardly improved on the guess).
//
// Fewer than min_tie_points usable tie points (a blank or saturated UHI, no
// overlap with the RGB footage): nothing is solved, and the result says why
// (solved == false), so the caller keeps the sequential result.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/se3_bspline.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/frontend/visual_map.h"
#include "pipelines/georef/georef_bundle_adjuster.h"
#include "core/survey/ins_body_track.h"
#include "solvers/graph_solver.h"

namespace hsmap {

struct JointOptions {
  double pixel_sigma_px = 1.0;  // a keyframe's observations
  // The other posed frames' observations: sigma = pixel_sigma_px times this.
  // Their pixels share each track's accumulated drift: at 5 they still
  // stretched the transect's along-track drift by a tenth; at 10 the
  // trajectory keeps the keyframe adjustment's shape (docs/JOINT.md, "Weights").
  double other_frame_sigma_factor = 10.0;
  double huber_sigmas = 2.0;
  // An observation farther than this from its landmark's projection at the
  // start is left out (it was an outlier of the front-end's PnP).
  double start_gate_px = 4.0;
  double sigma_match_m = 0.005;  // a tie point's 1-sigma on the ground, across the line
  // Along the line (the track) when > 0; else sigma_match_m. Tie points
  // matched in the push-broom strip (strip_tie_points.h) are finer across
  // the track than along it.
  double sigma_match_along_m = 0.0;
  double tie_robust_scale = 3.0;  // Cauchy, in sigmas
  int min_tie_points = 20;
  int min_frames_in_support = 3;
  // ... and at least this much of the frames' B-spline basis weight (one
  // frame's worth): the control points past the last posed frame.
  double min_frame_weight_in_support = 1.0;
  double sigma_linear_acceleration = 0.5;   // m/s^2, the smoothness prior
  double sigma_angular_acceleration = 0.5;  // rad/s^2
  double weak_fraction_of_prior = 0.5;
  // An estimated UHI intrinsic is reported inseparable when its correlation
  // with a component of T_C_U or d exceeds this, or its 1-sigma is above
  // weak_fraction_of_prior of its prior's.
  double inseparable_correlation = 0.95;
  int max_iterations = 30;
  int num_threads = 0;  // 0: every hardware thread
  // When d ends the solve at the bound of the tie factors' window (+-0.45
  // knot intervals from its start), the problem is built again around the
  // new d (each tie factor's control points chosen anew) and solved from
  // the result, at most this many times: a time offset guess several knot
  // intervals off converges in one call instead of asking for more rounds.
  int max_rewindows = 3;

  // std::invalid_argument naming the field and what was expected (every
  // sigma, scale and fraction > 0, counts >= their least useful value).
  // solveJointProblem calls it.
  void validate() const;
};

// A UHI pixel of scan line `line` (recorded time t_recorded) that saw p_W.
struct JointTiePoint {
  long long line = 0;
  double t_recorded = 0.0;
  double sample = 0.0;
  double range_m = 0.0;  // <= 0: 2 m
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
};

struct JointInputs {
  SE3Splined spline{0.0, 1.0, std::vector<SE3d>(4)};  // initial T_W_C(t)
  const VisualMap* map_W = nullptr;                    // landmarks in W (valid ones used)
  const FrontendResult* frontend = nullptr;            // frame observations
  const std::vector<double>* frame_times = nullptr;    // survey frame index -> time
  const InsBodyTrack* ins = nullptr;
  std::set<int> excluded_fixes;  // indices into ins->fixes()
  SE3d T_B_C;
  InsNoise ins_noise;
  std::vector<JointTiePoint> tie_points;
  // The trajectory the tie points' surface was made with. When given, each
  // tie point is carried by the spline (PushbroomCameraPointFactor: p_C at
  // its line's time), so a shift of the whole trajectory during the solve
  // (its absolute position is the INS's, to decimetres) cannot pull T_C_U;
  // null: the points are fixed in W (PushbroomLineFactor).
  const SE3Splined* surface_trajectory = nullptr;
  PinholeRadtanParameters rgb_camera;
  PushbroomParameters uhi_camera;
  SE3d T_C_U_prior;
  double sigma_rotation_deg = 2.0;
  double sigma_translation_m = 0.05;
  double time_offset_prior_s = 0.0;
  double time_offset_sigma_s = 0.05;
  SE3d T_C_U_start;  // where the solve starts (e.g. the last round's result)
  double time_offset_start_s = 0.0;
  // 1-sigma of uhi_camera's [f cx k1 k2] (survey.yaml's uhi.camera_sigma):
  // all 0 (the default) holds the intrinsics at uhi_camera; otherwise they
  // are estimated with uhi_camera as their prior.
  std::array<double, PushbroomCamera::kNumIntrinsics> uhi_intrinsics_sigma{};
  // Where the estimated intrinsics start (e.g. the last round's result);
  // nullopt: at uhi_camera.
  std::optional<std::array<double, PushbroomCamera::kNumIntrinsics>> uhi_intrinsics_start;

  bool estimatesUhiIntrinsics() const;
};

struct JointResult {
  bool solved = false;
  SE3Splined spline{0.0, 1.0, std::vector<SE3d>(4)};
  std::vector<std::pair<int, Eigen::Vector3d>> landmarks_W;  // (id, p_W) adjusted
  SE3d T_C_U;
  double time_offset_s = 0.0;
  // 1-sigma: rotation about U's x, y, z (deg), translation along C's x, y,
  // z (m), d (s); nullopt when the covariance could not be computed.
  std::optional<Eigen::Vector3d> sigma_rotation_deg;
  std::optional<Eigen::Vector3d> sigma_translation_m;
  std::optional<double> time_offset_sigma_s;
  // The UHI intrinsics [f cx k1 k2] as solved (nullopt: not estimated) and
  // their 1-sigma from the same covariance (0 for a parameter held; nullopt
  // when the covariance could not be computed).
  std::optional<std::array<double, PushbroomCamera::kNumIntrinsics>> uhi_intrinsics;
  std::optional<std::array<double, PushbroomCamera::kNumIntrinsics>> uhi_intrinsics_sigma;
  // Intrinsics the survey cannot separate from the extrinsic or d, each as
  // a sentence for calibration.yaml's warnings, e.g. "uhi_camera.cx cannot
  // be separated from T_C_U's rotation about U's y (the line's normal) on
  // this survey (correlation 0.98)".
  std::vector<std::string> inseparable_intrinsics;
  // Components the survey leaves weakly determined, e.g. "T_C_U rotation about U's x".
  std::vector<std::string> weakly_determined;
  // d ended at the bound of this solve's window: another round is needed
  // (a warning says so too, for people).
  bool time_offset_at_bound = false;

  int frames = 0;
  int reprojection_factors = 0;
  int keyframe_reprojection_factors = 0;  // of them, a keyframe's (at pixel_sigma_px)
  int gated_observations = 0;  // left out at the start (start_gate_px)
  int ins_position_factors = 0;
  int ins_attitude_factors = 0;
  int smoothness_factors = 0;
  int tie_points_given = 0;
  int tie_points_outside_spline = 0;
  int tie_inliers = 0;
  int tie_outliers = 0;
  int rewindows = 0;  // times the problem was built again around a new d (max_rewindows)
  // The inlier tie points' residuals after the final solve, on the ground
  // (metres at each pixel's range): RMS across and along the line.
  double rms_tie_across_m = 0.0, rms_tie_along_m = 0.0;
  SolveReport first_solve, last_solve;
  double seconds_covariance = 0.0;
  std::vector<std::string> warnings;

  // A few lines for the run's log.
  std::string summary() const;
};

// Solves the joint problem (see the header comment). Throws
// std::invalid_argument for missing inputs.
JointResult solveJointProblem(const JointInputs& inputs, const JointOptions& options = {});

}  // namespace hsmap
