#include "pipelines/evaluate/view_alignment.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hsmap {
namespace {

// sqrt(mean_i |p_i - mean p|^2).
double rmsSpread(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) sum += (p - mean).squaredNorm();
  return std::sqrt(sum / static_cast<double>(points.size()));
}

}  // namespace

void ViewAlignmentOptions::validate() const {
  if (max_iterations < 1) {
    throw std::invalid_argument("ViewAlignmentOptions: max_iterations must be >= 1");
  }
  if (!std::isfinite(scale_tolerance) || scale_tolerance <= 0.0) {
    throw std::invalid_argument("ViewAlignmentOptions: scale_tolerance must be finite and > 0");
  }
}

ViewAlignment alignFramesByView(const std::vector<TimedPose>& frames_est,
                                const std::vector<TimedPose>& frames_true, double view_distance_m,
                                const ViewAlignmentOptions& options) {
  options.validate();
  if (frames_est.size() != frames_true.size() || frames_est.empty()) {
    throw std::invalid_argument("expected as many estimated as true frames, at least one");
  }
  if (!std::isfinite(view_distance_m) || view_distance_m <= 0.0) {
    throw std::invalid_argument("the view distance must be finite and > 0");
  }
  const double h = view_distance_m;
  const std::size_t n = frames_est.size();
  std::vector<Eigen::Vector3d> centres_est(n), centres_true(n), axes_est(n);
  std::vector<Eigen::Vector3d> targets;  // every true centre, then every true view point
  targets.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    centres_est[i] = frames_est[i].T.t;
    centres_true[i] = frames_true[i].T.t;
    axes_est[i] = frames_est[i].T.q * Eigen::Vector3d::UnitZ();
    targets.push_back(centres_true[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    targets.push_back(centres_true[i] + h * (frames_true[i].T.q * Eigen::Vector3d::UnitZ()));
  }

  // The start: exact for a run that is the truth under a similarity.
  const double spread_est = rmsSpread(centres_est), spread_true = rmsSpread(centres_true);
  if (!(spread_est > 0.0) || !(spread_true > 0.0)) {
    throw std::invalid_argument(
        "the camera centres all coincide: the view points alone cannot fix the scale");
  }
  double s = spread_true / spread_est;
  std::vector<Eigen::Vector3d> sources(2 * n);
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    for (std::size_t i = 0; i < n; ++i) {
      sources[i] = centres_est[i];
      sources[n + i] = centres_est[i] + (h / s) * axes_est[i];
    }
    const Sim3 S_true_est = alignUmeyama(sources, targets);
    const double change = std::abs(S_true_est.scale() - s);
    s = S_true_est.scale();
    if (change <= options.scale_tolerance * s) return {S_true_est, iteration};
  }
  std::ostringstream why;
  why << "the scale did not settle in " << options.max_iterations << " Umeyama fits (last " << s
      << ")";
  throw std::invalid_argument(why.str());
}

}  // namespace hsmap
