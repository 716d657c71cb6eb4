#pragma once
// Interpolation of poses between timed samples (camera keyframes, INS
// records), for looking up a pose at a time that falls between two samples.
//
// interpolatePose(T_a, T_b, alpha), alpha in [0, 1]:
//   rotation     q_a * exp(alpha * log(q_a^-1 q_b))   (SO(3) geodesic: slerp
//                along the shorter arc, constant angular rate; so3.h)
//   translation  (1 - alpha) t_a + alpha t_b          (straight line)
// Rotation and translation are interpolated separately on purpose, not as
// the screw motion SE3d::interpolate() (a * exp(alpha log(a^-1 b))): with
// the screw the path of the origin depends on the rotation, so a vehicle
// that turns while moving straight would be interpolated along an arc, and
// the interpolated centre would change with the choice of the body origin.
// Between closely spaced samples of a vehicle (INS at 10-100 Hz, keyframes a
// fraction of a second apart) the straight line is the better model of the
// position, and it is exact for constant linear velocity with a constant
// angular velocity (tests/core/geometry/pose_interpolation_test.cc).
// alpha = 0 and 1 return T_a and T_b exactly; alpha outside [0, 1] (or not
// finite) throws std::invalid_argument: this is interpolation only, never
// extrapolation.
//
// TimedPoseTrajectory: samples T_W_X(t_k) at strictly increasing times.
// at(t) interpolates between the two samples that bracket t; at a sample
// time it returns that sample exactly. Outside [t_first, t_last] nothing is
// extrapolated or held: at(t) throws std::out_of_range naming t and the span,
// and covers(t) says beforehand whether t is inside. A trajectory of one
// sample covers only its own time.

#include <cstddef>
#include <vector>

#include "core/geometry/se3.h"

namespace hsmap {

SE3d interpolatePose(const SE3d& T_a, const SE3d& T_b, double alpha);

class TimedPoseTrajectory {
 public:
  // Throws std::invalid_argument for no samples, sizes that differ, a time
  // that is not finite or not strictly greater than the previous one (naming
  // the index and both times).
  TimedPoseTrajectory(std::vector<double> times, std::vector<SE3d> poses);

  // t_first <= t <= t_last (false for NaN).
  bool covers(double t) const;
  // The pose at time t; std::out_of_range when !covers(t).
  SE3d at(double t) const;

  double startTime() const { return times_.front(); }
  double endTime() const { return times_.back(); }
  std::size_t size() const { return times_.size(); }
  const std::vector<double>& times() const { return times_; }
  const std::vector<SE3d>& poses() const { return poses_; }

 private:
  std::vector<double> times_;
  std::vector<SE3d> poses_;
};

}  // namespace hsmap
