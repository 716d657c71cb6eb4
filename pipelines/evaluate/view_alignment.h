#pragma once
// The frames' view Sim(3) (DATASET.md, "uhi_position_rmse_m"): the similarity
// S_true_est = (s, R, t) that maps a run's W onto the truth's, fitted by
// Umeyama (alignUmeyama, i.e. Eigen::umeyama) over every matched frame i to
// TWO points per frame:
//   its camera centre       c_est(i)                        -> c_true(i)
//   its view point          c_est(i) + (h / s) a_est(i)     -> c_true(i) + h a_true(i)
// with a the optical axis (z of C) in W and h the view distance
// (view_distance.h: the median distance, over the true frames, from the true
// camera centre along its axis to the true surface). h is in the truth's
// metres, so the estimate's view point lies h / s along its own axis: under
// S it lands h along the mapped axis, s R (h / s) a_est = h R a_est.
//
// Why two points. The camera centres alone (the positions-only Umeyama of
// rgb_ate_aligned_m) leave the roll about a straight track to the track's
// sideways scatter: millimetres of position error then tilt everything the
// alignment maps. The view points, h below the cameras, pin that rotation
// through the cameras' orientations, weighted by what they see on the ground.
//
// Solving. The sources depend on s, the scale being solved for, so the fit is
// the fixed point s = scale(Umeyama with view points at h / s): starting from
// the ratio of the RMS spreads of the true and estimated camera centres about
// their means (exact when the run is the truth under a similarity), Umeyama
// is fitted with h / s_prev and refitted until the scale changes by less than
// scale_tolerance (relative). A run that is the truth under any similarity S0
// is recovered exactly: with s_prev = s0 both point sets are S0-related, so
// Umeyama returns S0^-1 and the iteration stops at once. Otherwise each step
// divides the scale's error by about 1 + (spread of the centres)^2 /
// (spread of the view offsets)^2: quickly on a long track, slowly on a short
// one (the `tiny` preset's 1.2 m track seen from 1.2 m: ~120 fits, a few
// milliseconds).

#include <vector>

#include "core/geometry/sim3.h"
#include "core/survey/pose_tables.h"

namespace hsmap {

struct ViewAlignmentOptions {
  int max_iterations = 5000;
  double scale_tolerance = 1e-12;  // relative change of s that ends the iteration

  // std::invalid_argument naming the field when out of range.
  void validate() const;
};

struct ViewAlignment {
  Sim3 S_true_est;      // p_true = s R p_est + t
  int iterations = 0;   // Umeyama fits made
};

// Frames paired by index. Throws std::invalid_argument with the reason when
// the alignment is undetermined: sizes differ or no frame, h not finite and
// > 0, the estimated or true camera centres all coincide (the view points
// carry no scale), the points are degenerate for Umeyama (alignUmeyama's
// reasons), or the scale does not settle within max_iterations.
ViewAlignment alignFramesByView(const std::vector<TimedPose>& frames_est,
                                const std::vector<TimedPose>& frames_true, double view_distance_m,
                                const ViewAlignmentOptions& options = {});

}  // namespace hsmap
