#include "core/geometry/pose_interpolation.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/geometry/so3.h"

namespace hsmap {

namespace {

// Times print with enough digits to tell neighbouring samples apart (INS
// times are often seconds of the day or Unix seconds).
std::string formatTime(double t) {
  std::ostringstream text;
  text << std::setprecision(15) << t;
  return text.str();
}

}  // namespace

SE3d interpolatePose(const SE3d& T_a, const SE3d& T_b, double alpha) {
  if (!(alpha >= 0.0 && alpha <= 1.0)) {
    std::ostringstream message;
    message << "interpolatePose: alpha must lie in [0, 1] (no extrapolation), got " << alpha;
    throw std::invalid_argument(message.str());
  }
  // The geodesic only reproduces its ends up to rounding; the ends are exact.
  if (alpha == 0.0) return T_a;
  if (alpha == 1.0) return T_b;
  return SE3d(interpolateSO3(T_a.q, T_b.q, alpha), (1.0 - alpha) * T_a.t + alpha * T_b.t);
}

TimedPoseTrajectory::TimedPoseTrajectory(std::vector<double> times, std::vector<SE3d> poses)
    : times_(std::move(times)), poses_(std::move(poses)) {
  if (times_.empty()) throw std::invalid_argument("TimedPoseTrajectory: no samples");
  if (times_.size() != poses_.size()) {
    throw std::invalid_argument("TimedPoseTrajectory: times and poses must pair up, got " +
                                std::to_string(times_.size()) + " times and " +
                                std::to_string(poses_.size()) + " poses");
  }
  for (std::size_t k = 0; k < times_.size(); ++k) {
    if (!std::isfinite(times_[k])) {
      throw std::invalid_argument("TimedPoseTrajectory: time " + std::to_string(k) +
                                  " is not finite (" + formatTime(times_[k]) + ")");
    }
    if (k > 0 && !(times_[k] > times_[k - 1])) {
      throw std::invalid_argument("TimedPoseTrajectory: times must increase strictly, but time " +
                                  std::to_string(k) + " (" + formatTime(times_[k]) +
                                  " s) follows " + formatTime(times_[k - 1]) + " s");
    }
  }
}

bool TimedPoseTrajectory::covers(double t) const {
  return t >= times_.front() && t <= times_.back();
}

SE3d TimedPoseTrajectory::at(double t) const {
  if (!covers(t)) {
    throw std::out_of_range("TimedPoseTrajectory: t = " + formatTime(t) +
                            " s is outside the trajectory's span [" + formatTime(times_.front()) +
                            ", " + formatTime(times_.back()) + "] s (no extrapolation)");
  }
  if (times_.size() == 1) return poses_.front();
  // The segment [t_k, t_k+1] with t_k <= t; t = t_last falls in the last one.
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const std::size_t k = std::min(static_cast<std::size_t>(after - times_.begin()) - 1,
                                 times_.size() - 2);
  const double alpha = (t - times_[k]) / (times_[k + 1] - times_[k]);
  return interpolatePose(poses_[k], poses_[k + 1], std::min(alpha, 1.0));
}

}  // namespace hsmap
