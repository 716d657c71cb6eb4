#include "core/survey/ins_body_track.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/so3.h"
#include "core/survey/ins_fixes_in_world.h"
#include "core/survey/survey.h"

namespace hsmap {
namespace {

std::vector<InsBodyFix> bodyFixes(const Survey& survey) {
  std::vector<InsBodyFix> fixes;
  for (const InsFixInWorld& fix : insFixesInWorld(survey)) {
    fixes.push_back({fix.t, fix.p_W_B, fix.q_W_B.value_or(Eigen::Quaterniond::Identity()),
                     fix.line_number});
  }
  return fixes;
}

InsBodyTrackOptions withHeadingWindow(double heading_window_s) {
  InsBodyTrackOptions options;
  options.heading_window_s = heading_window_s;
  return options;
}

}  // namespace

InsBodyTrack::InsBodyTrack(const Survey& survey, double heading_window_s)
    : InsBodyTrack(survey, withHeadingWindow(heading_window_s)) {}

InsBodyTrack::InsBodyTrack(const Survey& survey, const InsBodyTrackOptions& options)
    : InsBodyTrack(bodyFixes(survey), survey.ins.has_attitude, options) {}

InsBodyTrack::InsBodyTrack(std::vector<InsBodyFix> fixes, bool has_attitude,
                           double heading_window_s)
    : InsBodyTrack(std::move(fixes), has_attitude, withHeadingWindow(heading_window_s)) {}

InsBodyTrack::InsBodyTrack(std::vector<InsBodyFix> fixes, bool has_attitude,
                           const InsBodyTrackOptions& options)
    : fixes_(std::move(fixes)),
      has_attitude_(has_attitude),
      attitude_interpolation_(options.attitude_interpolation) {
  if (fixes_.empty()) throw std::invalid_argument("InsBodyTrack: no INS fixes");
  for (std::size_t i = 0; i < fixes_.size(); ++i) {
    if (i > 0 && !(fixes_[i].t > fixes_[i - 1].t)) {
      std::ostringstream message;
      message << "InsBodyTrack: fix " << i << " at t = " << fixes_[i].t
              << " s does not follow the previous one (t = " << fixes_[i - 1].t << " s)";
      throw std::invalid_argument(message.str());
    }
    times_.push_back(fixes_[i].t);
  }
  if (!has_attitude_ && options.derive_attitude) deriveAlongTrackAttitude(options.heading_window_s);
}

void InsBodyTrack::deriveAlongTrackAttitude(double heading_window_s) {
  // Direction of travel: the least-squares slope of north and east against
  // time over the fixes within half a window of each fix (at least its two
  // neighbours), so fix noise averages out along the track.
  const double half = 0.5 * heading_window_s;
  double last_heading = 0.0;
  for (std::size_t i = 0; i < fixes_.size(); ++i) {
    std::size_t first = i, last = i;
    while (first > 0 && fixes_[i].t - fixes_[first - 1].t <= half) --first;
    while (last + 1 < fixes_.size() && fixes_[last + 1].t - fixes_[i].t <= half) ++last;
    if (first == last) {
      if (first > 0) --first;
      if (last + 1 < fixes_.size()) ++last;
    }
    double mean_t = 0.0;
    Eigen::Vector2d mean_p = Eigen::Vector2d::Zero();
    const double n = double(last - first + 1);
    for (std::size_t j = first; j <= last; ++j) {
      mean_t += fixes_[j].t / n;
      mean_p += fixes_[j].p_W_B.head<2>() / n;
    }
    double stt = 0.0;
    Eigen::Vector2d stp = Eigen::Vector2d::Zero();
    for (std::size_t j = first; j <= last; ++j) {
      const double dt = fixes_[j].t - mean_t;
      stt += dt * dt;
      stp += dt * (fixes_[j].p_W_B.head<2>() - mean_p);
    }
    // A vehicle that holds still keeps the last heading it had.
    const Eigen::Vector2d velocity = stt > 0.0 ? Eigen::Vector2d(stp / stt) : Eigen::Vector2d::Zero();
    if (velocity.norm() > 1e-3) last_heading = std::atan2(velocity.y(), velocity.x());
    fixes_[i].q_W_B = Eigen::Quaterniond(Eigen::AngleAxisd(last_heading, Eigen::Vector3d::UnitZ()));
  }
}

bool InsBodyTrack::covers(double t) const { return t >= times_.front() && t <= times_.back(); }

double InsBodyTrack::fixInterval() const {
  if (times_.size() < 2) return 0.0;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < times_.size(); ++i) gaps.push_back(times_[i] - times_[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2];
}

SE3d InsBodyTrack::bodyPose(double t) const {
  if (!covers(t)) {
    std::ostringstream message;
    message << "InsBodyTrack: t = " << t << " s is outside the INS fixes [" << times_.front()
            << ", " << times_.back() << "] s";
    throw std::out_of_range(message.str());
  }
  auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (attitude_interpolation_ == InsAttitudeInterpolation::quaternion_slerp) {
    // The segment linker's arithmetic, kept to the bit: t at the last fix is
    // the end (alpha = 1) of the last interval, the position is blended as
    // (1 - alpha) p_a + alpha p_b at every alpha, the attitude slerped.
    if (fixes_.size() == 1) return SE3d(fixes_.front().q_W_B, fixes_.front().p_W_B);
    if (after == times_.end()) --after;
    const std::size_t i = std::size_t(after - times_.begin()) - 1;
    const double alpha = (t - times_[i]) / (times_[i + 1] - times_[i]);
    return SE3d(fixes_[i].q_W_B.slerp(alpha, fixes_[i + 1].q_W_B),
                (1.0 - alpha) * fixes_[i].p_W_B + alpha * fixes_[i + 1].p_W_B);
  }
  if (after == times_.end()) return SE3d(fixes_.back().q_W_B, fixes_.back().p_W_B);
  const std::size_t i = std::size_t(after - times_.begin()) - 1;
  const double alpha = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return interpolatePose(SE3d(fixes_[i].q_W_B, fixes_[i].p_W_B),
                         SE3d(fixes_[i + 1].q_W_B, fixes_[i + 1].p_W_B), alpha);
}

}  // namespace hsmap
