#include "pipelines/joint/joint_spline.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/geometry/pose_interpolation.h"

namespace hsmap {

SE3Splined splineThroughPoses(const std::vector<TimedPose>& frames, double dt_s) {
  if (frames.size() < 2) {
    throw std::invalid_argument("splineThroughPoses: need at least 2 frame poses, got " +
                                std::to_string(frames.size()));
  }
  if (!(std::isfinite(dt_s) && dt_s > 0.0)) {
    throw std::invalid_argument("splineThroughPoses: the knot spacing must be positive, got " +
                                std::to_string(dt_s));
  }
  std::vector<double> times;
  std::vector<SE3d> poses;
  for (const TimedPose& frame : frames) {
    times.push_back(frame.t);
    poses.push_back(frame.T);
  }
  const TimedPoseTrajectory trajectory(std::move(times), std::move(poses));
  const double t0 = trajectory.startTime();
  const double span = trajectory.endTime() - t0;
  // N - 3 segments must cover the span.
  const int segments = std::max(1, int(std::ceil(span / dt_s - 1e-9)));
  std::vector<SE3d> control_points;
  control_points.reserve(std::size_t(segments) + 3);
  for (int j = 0; j < segments + 3; ++j) {
    const double t = std::clamp(t0 + (j - 1) * dt_s, trajectory.startTime(), trajectory.endTime());
    control_points.push_back(trajectory.at(t));
  }
  return SE3Splined(t0, dt_s, std::move(control_points));
}

std::pair<double, double> splineDeviation(const SE3Splined& spline,
                                          const std::vector<TimedPose>& frames) {
  double sum_p = 0.0, sum_r = 0.0;
  int n = 0;
  for (const TimedPose& frame : frames) {
    if (frame.t < spline.validBegin() || frame.t > spline.validEnd()) continue;
    const SE3d T = spline.pose(frame.t);
    sum_p += (T.t - frame.T.t).squaredNorm();
    const double angle = frame.T.q.angularDistance(T.q);
    sum_r += angle * angle;
    ++n;
  }
  if (n == 0) return {0.0, 0.0};
  return {std::sqrt(sum_p / n), std::sqrt(sum_r / n) * 180.0 / std::numbers::pi};
}

std::pair<double, double> splineChange(const SE3Splined& before, const SE3Splined& after,
                                       const std::vector<double>& times) {
  std::vector<TimedPose> poses_before;
  poses_before.reserve(times.size());
  for (const double t : times) {
    if (t >= before.validBegin() && t <= before.validEnd()) poses_before.push_back({t, before.pose(t)});
  }
  return splineDeviation(after, poses_before);
}

KnotSpacingChoice chooseKnotSpacing(const std::vector<TimedPose>& frames,
                                    const JointSplineOptions& options) {
  if (frames.size() < 2) {
    throw std::invalid_argument("chooseKnotSpacing: need at least 2 frame poses, got " +
                                std::to_string(frames.size()));
  }
  std::vector<double> intervals;
  for (std::size_t i = 1; i < frames.size(); ++i) intervals.push_back(frames[i].t - frames[i - 1].t);
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  const double frame_interval = intervals[intervals.size() / 2];
  const double finest = 2.0 * frame_interval;

  std::vector<double> candidates;
  for (double dt : options.candidate_spacings_s) {
    if (dt >= finest) candidates.push_back(dt);
  }
  if (candidates.empty() || candidates.back() > finest * 1.0001) candidates.push_back(finest);
  std::sort(candidates.begin(), candidates.end(), std::greater<>());

  KnotSpacingChoice choice;
  for (double dt : candidates) {
    const auto [position, rotation] = splineDeviation(splineThroughPoses(frames, dt), frames);
    choice.dt_s = dt;
    choice.rms_position_m = position;
    choice.rms_rotation_deg = rotation;
    choice.within_tolerance =
        position <= options.tolerance_position_m && rotation <= options.tolerance_rotation_deg;
    if (choice.within_tolerance) break;
  }
  std::ostringstream reason;
  reason << "knot spacing " << choice.dt_s << " s (frames every " << frame_interval
         << " s): the initial spline follows the frame poses within " << choice.rms_position_m * 1000.0
         << " mm and " << choice.rms_rotation_deg << " deg RMS";
  if (!choice.within_tolerance) {
    reason << ", beyond the tolerance (" << options.tolerance_position_m * 1000.0 << " mm, "
           << options.tolerance_rotation_deg << " deg) even at the finest spacing";
  }
  choice.reason = reason.str();
  return choice;
}

}  // namespace hsmap
