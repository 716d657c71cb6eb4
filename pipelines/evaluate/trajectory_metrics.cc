#include "pipelines/evaluate/trajectory_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "core/geometry/rotation_anchored_alignment.h"
#include "core/geometry/so3.h"
#include "pipelines/evaluate/view_alignment.h"

namespace hsmap {
namespace {

double rms(double sum_of_squares, std::size_t count) {
  return std::sqrt(sum_of_squares / static_cast<double>(count));
}

struct LineErrors {
  MetricValue position_rmse_m;
  MetricValue rotation_rmse_deg;
};

// Every scan line's pose mapped by S_true_est against the truth, or `why`
// when there is no S_true_est.
LineErrors lineErrors(const std::optional<Sim3>& S_true_est, const std::string& why,
                      const std::vector<LinePose>& lines_est,
                      const std::vector<LinePose>& lines_true) {
  if (!S_true_est) return {MetricValue::missing(why), MetricValue::missing(why)};
  if (lines_est.empty()) return {MetricValue::missing("no scan lines"), MetricValue::missing("no scan lines")};
  double position_sum = 0.0;
  double angle_sum = 0.0;
  for (std::size_t k = 0; k < lines_est.size(); ++k) {
    // transformPose maps the UHI centre by s R p + t and turns its axes by R.
    const SE3d T_true_U = S_true_est->transformPose(lines_est[k].T);
    position_sum += (T_true_U.t - lines_true[k].T.t).squaredNorm();
    const double angle = rotationAngleDeg(lines_true[k].T.q, T_true_U.q);
    angle_sum += angle * angle;
  }
  return {MetricValue::of(rms(position_sum, lines_est.size())),
          MetricValue::of(rms(angle_sum, lines_est.size()))};
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
                                           const std::vector<LinePose>& lines_true,
                                           const MetricValue& view_distance_m) {
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

  metrics.alignment_view_distance_m = view_distance_m;
  if (!view_distance_m.value) {
    metrics.why_no_view_alignment = "no view alignment of the frames: " + view_distance_m.reason;
  } else {
    try {
      const ViewAlignment view = alignFramesByView(frames_est, frames_true, *view_distance_m.value);
      metrics.S_true_est_view = view.S_true_est;
      metrics.view_alignment_iterations = view.iterations;
    } catch (const std::invalid_argument& e) {
      metrics.why_no_view_alignment = std::string("no view alignment of the frames: ") + e.what();
    }
  }
  const LineErrors view =
      lineErrors(metrics.S_true_est_view, metrics.why_no_view_alignment, lines_est, lines_true);
  metrics.uhi_position_rmse_m = view.position_rmse_m;
  metrics.uhi_rotation_rmse_deg = view.rotation_rmse_deg;

  try {
    metrics.S_true_est = alignUmeyama(p_est, p_true);
  } catch (const std::invalid_argument& e) {
    metrics.why_no_alignment =
        std::string("no similarity alignment of the frame positions: ") + e.what();
    metrics.rgb_ate_aligned_m = MetricValue::missing(metrics.why_no_alignment);
    metrics.rgb_scale_error = MetricValue::missing(metrics.why_no_alignment);
  }
  if (metrics.S_true_est) {
    const Sim3& S = *metrics.S_true_est;
    sum = 0.0;
    for (std::size_t i = 0; i < p_est.size(); ++i) sum += (S.apply(p_est[i]) - p_true[i]).squaredNorm();
    metrics.rgb_ate_aligned_m = MetricValue::of(rms(sum, p_est.size()));
    metrics.rgb_scale_error = MetricValue::of(std::abs(S.scale() - 1.0));
  }
  const LineErrors positions =
      lineErrors(metrics.S_true_est, metrics.why_no_alignment, lines_est, lines_true);
  metrics.uhi_position_rmse_positions_aligned_m = positions.position_rmse_m;
  metrics.uhi_rotation_rmse_positions_aligned_deg = positions.rotation_rmse_deg;
  return metrics;
}

}  // namespace hsmap
