#include "pipelines/georef/camera_trajectory.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/geometry/pose_interpolation.h"

namespace hsmap {

const char* toString(PoseSource source) {
  switch (source) {
    case PoseSource::vision: return "vision";
    case PoseSource::ins_bridged: return "ins_bridged";
    case PoseSource::ins_only: return "ins_only";
    case PoseSource::held: return "held";
  }
  return "?";
}

CameraTrajectory::CameraTrajectory(std::vector<double> times, std::vector<SE3d> T_W_C,
                                   const InsBodyTrack* ins, const SE3d& T_B_C,
                                   double max_vision_gap_s)
    : times_(std::move(times)),
      T_W_C_(std::move(T_W_C)),
      ins_(ins),
      T_B_C_(T_B_C),
      max_vision_gap_s_(max_vision_gap_s) {
  if (times_.size() != T_W_C_.size()) {
    throw std::invalid_argument("CameraTrajectory: times and poses differ in number");
  }
  for (std::size_t i = 1; i < times_.size(); ++i) {
    if (!(times_[i] > times_[i - 1])) {
      std::ostringstream message;
      message << "CameraTrajectory: frame time " << times_[i] << " s does not follow "
              << times_[i - 1] << " s";
      throw std::invalid_argument(message.str());
    }
  }
  if (times_.empty() && ins_ == nullptr) {
    throw std::invalid_argument("CameraTrajectory: no posed frame and no INS");
  }
}

bool CameraTrajectory::insCamera(double t, SE3d& T_W_C) const {
  if (ins_ == nullptr || !ins_->covers(t)) return false;
  T_W_C = ins_->bodyPose(t) * T_B_C_;
  return true;
}

bool CameraTrajectory::offsetAt(std::size_t i, SE3d& D) const {
  SE3d T_ins;
  if (!insCamera(times_[i], T_ins)) return false;
  // Position offset in W (where the INS errs: its fixes), rotation offset
  // in C (the INS's attitude error and mounting act on the vehicle's axes).
  // A single left-multiplied SE(3) offset would couple a small rotation
  // error with the distance from W's origin into a large translation.
  D = SE3d(T_ins.q.conjugate() * T_W_C_[i].q, T_W_C_[i].t - T_ins.t);
  return true;
}

TimedCameraPose CameraTrajectory::heldAt(double t) const {
  if (!times_.empty()) {
    const std::size_t i = t <= times_.front() ? 0 : times_.size() - 1;
    if (t > times_.front() && t < times_.back()) {
      // Inside a gap the INS cannot reach: the nearer side.
      const auto after = std::upper_bound(times_.begin(), times_.end(), t);
      const std::size_t b = std::size_t(after - times_.begin());
      const std::size_t nearer = (t - times_[b - 1] <= times_[b] - t) ? b - 1 : b;
      return {T_W_C_[nearer], PoseSource::held};
    }
    return {T_W_C_[i], PoseSource::held};
  }
  const double clamped = std::clamp(t, ins_->startTime(), ins_->endTime());
  return {ins_->bodyPose(clamped) * T_B_C_, PoseSource::held};
}

bool CameraTrajectory::visionCovers(double t) const {
  if (times_.empty() || !(t >= times_.front() && t <= times_.back())) return false;
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (after == times_.end()) return true;  // t is the last frame's time
  const std::size_t b = std::size_t(after - times_.begin());
  return times_[b] - times_[b - 1] <= max_vision_gap_s_ || t == times_[b - 1];
}

TimedCameraPose CameraTrajectory::at(double t) const {
  if (times_.empty()) {
    SE3d T_ins;
    if (insCamera(t, T_ins)) return {T_ins, PoseSource::ins_only};
    return heldAt(t);
  }
  if (visionCovers(t)) {
    const auto after = std::upper_bound(times_.begin(), times_.end(), t);
    if (after == times_.end()) return {T_W_C_.back(), PoseSource::vision};
    const std::size_t b = std::size_t(after - times_.begin());
    const double alpha = (t - times_[b - 1]) / (times_[b] - times_[b - 1]);
    return {interpolatePose(T_W_C_[b - 1], T_W_C_[b], alpha), PoseSource::vision};
  }
  SE3d T_ins;
  if (!insCamera(t, T_ins)) return heldAt(t);
  // The vision frames on either side of t (one side may not exist).
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  const bool has_after = after != times_.end();
  const bool has_before = after != times_.begin();
  SE3d D_before, D_after;
  const bool ok_before = has_before && offsetAt(std::size_t(after - times_.begin()) - 1, D_before);
  const bool ok_after = has_after && offsetAt(std::size_t(after - times_.begin()), D_after);
  SE3d D;
  if (ok_before && ok_after) {
    const std::size_t b = std::size_t(after - times_.begin());
    const double alpha = (t - times_[b - 1]) / (times_[b] - times_[b - 1]);
    D = interpolatePose(D_before, D_after, alpha);
  } else if (ok_before) {
    D = D_before;
  } else if (ok_after) {
    D = D_after;
  } else {
    return {T_ins, PoseSource::ins_only};
  }
  return {SE3d((T_ins.q * D.q).normalized(), T_ins.t + D.t), PoseSource::ins_bridged};
}

}  // namespace hsmap
