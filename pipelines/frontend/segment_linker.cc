#include "pipelines/frontend/segment_linker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/geometry/rotation_anchored_alignment.h"
#include "core/survey/ins_fixes_in_world.h"
#include "core/survey/survey.h"

namespace hsmap {

InsCameraTrack::InsCameraTrack(const Survey& survey)
    : has_attitude_(survey.ins.has_attitude),
      T_B_C_(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m) {
  for (const InsFixInWorld& fix : insFixesInWorld(survey)) {
    times_.push_back(fix.t);
    p_W_B_.push_back(fix.p_W_B);
    q_W_B_.push_back(fix.q_W_B.value_or(Eigen::Quaterniond::Identity()));
  }
}

InsCameraTrack::InsCameraTrack(std::vector<double> times, std::vector<Eigen::Vector3d> p_W_B,
                               std::vector<Eigen::Quaterniond> q_W_B, bool has_attitude,
                               const SE3d& T_B_C)
    : times_(std::move(times)),
      p_W_B_(std::move(p_W_B)),
      q_W_B_(std::move(q_W_B)),
      has_attitude_(has_attitude),
      T_B_C_(T_B_C) {
  if (times_.empty() || p_W_B_.size() != times_.size() || q_W_B_.size() != times_.size()) {
    throw std::invalid_argument("InsCameraTrack: times, positions and attitudes must match");
  }
}

bool InsCameraTrack::covers(double t) const {
  return !times_.empty() && t >= times_.front() && t <= times_.back();
}

double InsCameraTrack::fixInterval() const {
  if (times_.size() < 2) return 0.0;
  std::vector<double> gaps;
  for (std::size_t i = 1; i < times_.size(); ++i) gaps.push_back(times_[i] - times_[i - 1]);
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2];
}

std::size_t InsCameraTrack::segmentIndex(double t, double* alpha) const {
  if (!covers(t)) throw std::out_of_range("InsCameraTrack: time outside the INS fixes");
  if (times_.size() == 1) {
    *alpha = 0.0;
    return 0;
  }
  auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (after == times_.end()) --after;
  const std::size_t i = std::size_t(after - times_.begin()) - 1;
  *alpha = (t - times_[i]) / (times_[i + 1] - times_[i]);
  return i;
}

Eigen::Vector3d InsCameraTrack::bodyPosition(double t) const {
  double alpha = 0.0;
  const std::size_t i = segmentIndex(t, &alpha);
  if (times_.size() == 1) return p_W_B_[0];
  return (1.0 - alpha) * p_W_B_[i] + alpha * p_W_B_[i + 1];
}

Eigen::Quaterniond InsCameraTrack::bodyAttitude(double t) const {
  double alpha = 0.0;
  const std::size_t i = segmentIndex(t, &alpha);
  if (times_.size() == 1) return q_W_B_[0];
  return q_W_B_[i].slerp(alpha, q_W_B_[i + 1]);
}


SegmentFit fitSegmentToIns(const std::vector<double>& times, const std::vector<SE3d>& T_S_C,
                           const InsCameraTrack& ins, int min_keyframes) {
  SegmentFit fit;
  std::vector<Eigen::Vector3d> p_S, p_W_B;
  std::vector<Eigen::Quaterniond> q_S_C, q_W_B;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!ins.covers(times[i])) continue;
    p_S.push_back(T_S_C[i].t);
    q_S_C.push_back(T_S_C[i].q);
    p_W_B.push_back(ins.bodyPosition(times[i]));
    q_W_B.push_back(ins.bodyAttitude(times[i]));
  }
  fit.pairs = int(p_S.size());
  if (fit.pairs < min_keyframes) {
    fit.failure = std::to_string(fit.pairs) + " keyframes inside the INS span, fewer than " +
                  std::to_string(min_keyframes);
    return fit;
  }
  double t_min = 1e300, t_max = -1e300;
  for (double t : times) {
    if (ins.covers(t)) {
      t_min = std::min(t_min, t);
      t_max = std::max(t_max, t);
    }
  }
  if (t_max - t_min < 2.0 * ins.fixInterval()) {
    fit.failure = "the segment spans less than two INS fix intervals";
    return fit;
  }
  const Eigen::Vector3d t_B_C = ins.T_B_C().t;
  const Eigen::Quaterniond q_B_C = ins.T_B_C().q;
  try {
    std::vector<Eigen::Vector3d> p_W_C(p_S.size());
    if (ins.hasAttitude()) {
      std::vector<Eigen::Quaterniond> q_W_S(p_S.size());
      for (std::size_t i = 0; i < p_S.size(); ++i) {
        p_W_C[i] = p_W_B[i] + q_W_B[i] * t_B_C;
        q_W_S[i] = q_W_B[i] * q_B_C * q_S_C[i].conjugate();
      }
      fit.S_W_S = alignScaleTranslation(chordalMeanRotation(q_W_S), p_S, p_W_C);
    } else {
      // No attitude: positions alone, lever arm from the fit's own rotation.
      for (std::size_t i = 0; i < p_S.size(); ++i) p_W_C[i] = p_W_B[i];
      fit.S_W_S = alignUmeyama(p_S, p_W_C, true);
      for (int round = 0; round < 2; ++round) {
        for (std::size_t i = 0; i < p_S.size(); ++i) {
          const Eigen::Quaterniond q_W_C = fit.S_W_S.rotation() * q_S_C[i];
          p_W_C[i] = p_W_B[i] + (q_W_C * q_B_C.conjugate()) * t_B_C;
        }
        fit.S_W_S = alignUmeyama(p_S, p_W_C, true);
      }
    }
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < p_S.size(); ++i) sum_sq += (fit.S_W_S.apply(p_S[i]) - p_W_C[i]).squaredNorm();
    fit.rms_m = std::sqrt(sum_sq / double(p_S.size()));
  } catch (const std::invalid_argument& error) {
    fit.failure = std::string("cannot fit: ") + error.what();
    return fit;
  }
  fit.ok = true;
  return fit;
}

}  // namespace hsmap
