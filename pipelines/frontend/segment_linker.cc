#include "pipelines/frontend/segment_linker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/geometry/rotation_anchored_alignment.h"

namespace hsmap {

SegmentFit fitSegmentToIns(const std::vector<double>& times, const std::vector<SE3d>& T_S_C,
                           const InsBodyTrack& ins, const SE3d& T_B_C, int min_keyframes,
                           double outlier_threshold_m) {
  SegmentFit fit;
  std::vector<Eigen::Vector3d> p_S, p_W_B;
  std::vector<Eigen::Quaterniond> q_S_C, q_W_B;
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!ins.covers(times[i])) continue;
    p_S.push_back(T_S_C[i].t);
    q_S_C.push_back(T_S_C[i].q);
    const SE3d T_W_B = ins.bodyPose(times[i]);
    p_W_B.push_back(T_W_B.t);
    q_W_B.push_back(T_W_B.q);
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
  const Eigen::Vector3d t_B_C = T_B_C.t;
  const Eigen::Quaterniond q_B_C = T_B_C.q;
  // Faulty fixes out first: RANSAC on the positions (the lever arm from the
  // INS attitude when there is one; without, the body positions, the lever
  // arm being far below the threshold).
  {
    std::vector<Eigen::Vector3d> p_W(p_S.size());
    for (std::size_t i = 0; i < p_S.size(); ++i) {
      p_W[i] = ins.hasAttitude() ? Eigen::Vector3d(p_W_B[i] + q_W_B[i] * t_B_C) : p_W_B[i];
    }
    std::vector<bool> keep(p_S.size(), true);
    try {
      keep = alignUmeyamaRobust(p_S, p_W, outlier_threshold_m, true).inliers;
    } catch (const std::exception& error) {
      fit.note = std::string("every fix kept (no RANSAC: ") + error.what() + ")";
    }
    std::size_t kept = 0;
    for (std::size_t i = 0; i < p_S.size(); ++i) {
      if (!keep[i]) continue;
      p_S[kept] = p_S[i];
      q_S_C[kept] = q_S_C[i];
      p_W_B[kept] = p_W_B[i];
      q_W_B[kept] = q_W_B[i];
      ++kept;
    }
    fit.outliers = int(p_S.size() - kept);
    for (auto* v : {&p_S, &p_W_B}) v->resize(kept);
    q_S_C.resize(kept);
    q_W_B.resize(kept);
  }
  if (int(p_S.size()) < min_keyframes) {
    fit.failure = std::to_string(p_S.size()) + " keyframes agree with the INS (" + std::to_string(fit.outliers) +
                  " left out as outliers), fewer than " + std::to_string(min_keyframes);
    return fit;
  }
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
    double sum_sq = 0.0, spread = 0.0;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : p_S) mean += p;
    mean /= double(p_S.size());
    for (std::size_t i = 0; i < p_S.size(); ++i) {
      sum_sq += (fit.S_W_S.apply(p_S[i]) - p_W_C[i]).squaredNorm();
      spread += (p_S[i] - mean).squaredNorm();
    }
    fit.rms_m = std::sqrt(sum_sq / double(p_S.size()));
    const double dof = std::max(1.0, 3.0 * double(p_S.size()) - 7.0);
    fit.scale_sigma = spread > 0.0 ? std::sqrt(sum_sq / dof / spread) : 0.0;
    fit.p_S = p_S;
    fit.p_W_C = p_W_C;
  } catch (const std::invalid_argument& error) {
    fit.failure = std::string("cannot fit: ") + error.what();
    return fit;
  }
  fit.ok = true;
  return fit;
}

Sim3 withScale(const SegmentFit& fit, double scale) {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < fit.p_S.size(); ++i) t += fit.p_W_C[i] - scale * (fit.S_W_S.rotation() * fit.p_S[i]);
  if (!fit.p_S.empty()) t /= double(fit.p_S.size());
  return Sim3(scale, fit.S_W_S.rotation(), t);
}

}  // namespace hsmap
