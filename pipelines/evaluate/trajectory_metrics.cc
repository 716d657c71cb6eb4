#include "pipelines/evaluate/trajectory_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "core/geometry/rotation_anchored_alignment.h"
#include "core/geometry/so3.h"

namespace hsmap {
namespace {

double rms(double sum_of_squares, std::size_t count) {
  return std::sqrt(sum_of_squares / static_cast<double>(count));
}

}  // namespace

double rotationAngleDeg(const Eigen::Quaterniond& q_a, const Eigen::Quaterniond& q_b) {
  // logSO3 picks the representative with w >= 0, so the angle is in [0, pi]
  // whatever the signs of the two quaternions.
  return logSO3(Eigen::Quaterniond(q_a.conjugate() * q_b)).norm() * so3_detail::kRadToDeg;
}

Sim3 alignFramesByAttitude(const std::vector<TimedPose>& frames_est,
                           const std::vector<TimedPose>& frames_true) {
  if (frames_est.size() != frames_true.size()) {
    throw std::invalid_argument("alignFramesByAttitude: expected as many estimated as true frames");
  }
  std::vector<Eigen::Quaterniond> q_true_est;
  std::vector<Eigen::Vector3d> p_est;
  std::vector<Eigen::Vector3d> p_true;
  for (std::size_t i = 0; i < frames_est.size(); ++i) {
    // R_true R_est^T maps the run's W onto the truth's as frame i sees it.
    q_true_est.push_back(frames_true[i].T.q * frames_est[i].T.q.conjugate());
    p_est.push_back(frames_est[i].T.t);
    p_true.push_back(frames_true[i].T.t);
  }
  return alignScaleTranslation(chordalMeanRotation(q_true_est), p_est, p_true);
}

double crossTrackSpread(const std::vector<Eigen::Vector3d>& positions) {
  if (positions.size() < 2) return 0.0;
  const double n = static_cast<double>(positions.size());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : positions) mean += p / n;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : positions) covariance += (p - mean) * (p - mean).transpose() / n;
  // Ascending eigenvalues: the middle one is the variance across the main
  // direction (clamped: rounding can make a zero eigenvalue slightly negative).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eigen.eigenvalues()(1)));
}

TrajectoryMetrics computeTrajectoryMetrics(const std::vector<TimedPose>& frames_est,
                                           const std::vector<TimedPose>& frames_true,
                                           const std::vector<LinePose>& lines_est,
                                           const std::vector<LinePose>& lines_true) {
  if (frames_est.size() != frames_true.size() || frames_est.empty() ||
      lines_est.size() != lines_true.size()) {
    throw std::invalid_argument(
        "computeTrajectoryMetrics: expected as many estimated as true frames (at least one) and "
        "scan lines");
  }
  TrajectoryMetrics metrics;
  std::vector<Eigen::Vector3d> p_est;
  std::vector<Eigen::Vector3d> p_true;
  double sum = 0.0;
  for (std::size_t i = 0; i < frames_est.size(); ++i) {
    p_est.push_back(frames_est[i].T.t);
    p_true.push_back(frames_true[i].T.t);
    sum += (p_est.back() - p_true.back()).squaredNorm();
  }
  metrics.rgb_ate_m = MetricValue::of(rms(sum, p_est.size()));

  metrics.alignment_cross_track_spread_m = MetricValue::of(crossTrackSpread(p_true));
  try {
    metrics.S_true_est_attitude = alignFramesByAttitude(frames_est, frames_true);
  } catch (const std::invalid_argument& e) {
    metrics.why_no_attitude_alignment =
        std::string("no attitude-anchored alignment of the frames: ") + e.what();
  }

  try {
    metrics.S_true_est = alignUmeyama(p_est, p_true);
  } catch (const std::invalid_argument& e) {
    const std::string why =
        std::string("no similarity alignment of the frame positions: ") + e.what();
    metrics.why_no_alignment = why;
    metrics.rgb_ate_aligned_m = MetricValue::missing(why);
    metrics.rgb_scale_error = MetricValue::missing(why);
    metrics.uhi_position_rmse_m = MetricValue::missing(why);
    metrics.uhi_rotation_rmse_deg = MetricValue::missing(why);
    return metrics;
  }
  const Sim3& S = *metrics.S_true_est;
  sum = 0.0;
  for (std::size_t i = 0; i < p_est.size(); ++i) sum += (S.apply(p_est[i]) - p_true[i]).squaredNorm();
  metrics.rgb_ate_aligned_m = MetricValue::of(rms(sum, p_est.size()));
  metrics.rgb_scale_error = MetricValue::of(std::abs(S.scale() - 1.0));

  if (lines_est.empty()) {
    metrics.uhi_position_rmse_m = MetricValue::missing("no scan lines");
    metrics.uhi_rotation_rmse_deg = MetricValue::missing("no scan lines");
    return metrics;
  }
  double position_sum = 0.0;
  double angle_sum = 0.0;
  for (std::size_t k = 0; k < lines_est.size(); ++k) {
    // transformPose maps the UHI centre by s R p + t and turns its axes by R.
    const SE3d T_true_U = S.transformPose(lines_est[k].T);
    position_sum += (T_true_U.t - lines_true[k].T.t).squaredNorm();
    const double angle = rotationAngleDeg(lines_true[k].T.q, T_true_U.q);
    angle_sum += angle * angle;
  }
  metrics.uhi_position_rmse_m = MetricValue::of(rms(position_sum, lines_est.size()));
  metrics.uhi_rotation_rmse_deg = MetricValue::of(rms(angle_sum, lines_est.size()));
  return metrics;
}

}  // namespace hsmap
