#pragma once
// The joint problem's trajectory: the RGB camera's pose T_W_C(t) as the
// engine's uniform cumulative cubic SE(3) B-spline (core/geometry/se3_bspline.h),
// initialised from the `sequential` frame poses.
//
// Initialisation. For a uniform cumulative cubic B-spline the pose at knot
// time t0 + k dt is a weighted mean (1/6, 4/6, 1/6) of control points k,
// k+1, k+2, so control point j is placed at the frames' pose interpolated at
// t0 + (j - 1) dt (held at the first / last frame beyond them). This is a
// smoothing approximation, not an interpolation: its error grows as
// dt^2 / 6 times the vehicle's acceleration, and the joint solve then fits
// the control points to the observations themselves.
//
// Knot spacing, from the vehicle's motion. Candidates from coarse to fine
// (JointSplineOptions::candidate_spacings_s, never below two frame
// intervals: a segment must hold observations of at least two frames). The
// spacing chosen is the coarsest whose initial spline follows the frame
// poses within the tolerance (RMS position and rotation over the frames);
// a vehicle that sways or pitches quickly gets a finer spline, a smooth
// straight run a coarser one (fewer control points, a better-determined
// solve). If none meets it, the finest is used and the result says so.

#include <string>
#include <vector>

#include "core/geometry/se3_bspline.h"
#include "core/survey/pose_tables.h"

namespace hsmap {

struct JointSplineOptions {
  std::vector<double> candidate_spacings_s = {0.4, 0.2, 0.1, 0.05};
  double tolerance_position_m = 0.002;   // RMS over the frames
  double tolerance_rotation_deg = 0.05;  // RMS over the frames
};

struct KnotSpacingChoice {
  double dt_s = 0.0;
  double rms_position_m = 0.0;   // of the initial spline against the frames
  double rms_rotation_deg = 0.0;
  bool within_tolerance = false;
  std::string reason;  // one sentence for the run's log
};

// The spline of the given spacing through `frames` (strictly increasing
// times, at least 2), valid over [first frame, last frame]. Throws
// std::invalid_argument for fewer than 2 frames or dt <= 0.
SE3Splined splineThroughPoses(const std::vector<TimedPose>& frames, double dt_s);

// RMS position (m) and rotation (deg) of the spline against the frames
// inside its valid range.
std::pair<double, double> splineDeviation(const SE3Splined& spline,
                                          const std::vector<TimedPose>& frames);

// RMS position (m) and rotation (deg) by which `after` differs from
// `before` at the given times (those inside both splines' valid ranges):
// how far a round of the joint stage moved the trajectory.
std::pair<double, double> splineChange(const SE3Splined& before, const SE3Splined& after,
                                       const std::vector<double>& times);

// The knot spacing for these frames (see the header comment).
KnotSpacingChoice chooseKnotSpacing(const std::vector<TimedPose>& frames,
                                    const JointSplineOptions& options = {});

}  // namespace hsmap
