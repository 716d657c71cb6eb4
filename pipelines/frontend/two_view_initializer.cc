#include "pipelines/frontend/two_view_initializer.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <sstream>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/reprojection_factor.h"
#include "pipelines/frontend/landmark_triangulator.h"
#include "solvers/graph_solver.h"

namespace hsmap {

namespace {

std::string describe(const char* what, double value, double limit) {
  std::ostringstream text;
  text << what << " " << value << " below " << limit;
  return text.str();
}

// The 5-point RANSAC model comes from five points only (OpenCV does not
// refit it on the inliers), which leaves errors of tenths of a degree that
// the local bundle adjustment could not undo later (it holds a segment's
// first two keyframes fixed). So: a two-view bundle adjustment with the
// engine over every landmark, the first camera held, the distorted pixels
// with the full lens model, a Huber loss; then landmarks that still
// reproject badly are dropped.
void refineTwoView(const std::vector<Eigen::Vector2d>& pixels1, const std::vector<Eigen::Vector2d>& pixels2,
                   const PinholeRadtanCamera& camera, const TwoViewOptions& options, SE3d& T_C1_C2,
                   std::vector<std::optional<Eigen::Vector3d>>& p_C1) {
  FactorGraph graph;
  Values values;
  const NoiseModel noise = NoiseModel::isotropic(2, 1.0);
  const RobustLoss loss = RobustLoss::huber(2.0);
  values.insertPose(X(0), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  values.insertPose(X(1), T_C1_C2.q, T_C1_C2.t);
  // The baseline's length is free (monocular); hold it by the distance of
  // the second camera: LM's damping keeps it near its start, and the scale is
  // normalised afterwards anyway.
  for (std::size_t i = 0; i < p_C1.size(); ++i) {
    if (!p_C1[i]) continue;
    values.insertPoint(L(i), *p_C1[i]);
    graph.emplace<ReprojectionFactor>(X(0), L(i), pixels1[i], camera.parameters(), noise, loss);
    graph.emplace<ReprojectionFactor>(X(1), L(i), pixels2[i], camera.parameters(), noise, loss);
  }
  SolverOptions solver;
  solver.max_iterations = 10;
  solver.num_threads = 1;
  const SolveReport report = solve(graph, values, solver, {X(0)});
  if (!report.usable) return;
  T_C1_C2 = SE3d(values.poseRotation(X(1)).normalized(), values.poseTranslation(X(1)));
  const SE3d T_C2_C1 = T_C1_C2.inverse();
  for (std::size_t i = 0; i < p_C1.size(); ++i) {
    if (!p_C1[i]) continue;
    const Eigen::Vector3d p = values.point(L(i));
    const Eigen::Vector3d p2 = T_C2_C1 * p;
    const bool good = p.z() > 0.0 && p2.z() > 0.0 &&
                      (camera.project(p) - pixels1[i]).norm() <= options.max_error_px &&
                      (camera.project(p2) - pixels2[i]).norm() <= options.max_error_px;
    if (good) {
      p_C1[i] = p;
    } else {
      p_C1[i].reset();
    }
  }
}

}  // namespace

TwoViewResult initializeTwoView(const std::vector<Eigen::Vector2d>& normalized1,
                                const std::vector<Eigen::Vector2d>& normalized2,
                                const std::vector<Eigen::Vector2d>& pixels1,
                                const std::vector<Eigen::Vector2d>& pixels2,
                                const PinholeRadtanCamera& camera, const TwoViewOptions& options) {
  TwoViewResult result;
  const std::size_t n = normalized1.size();
  result.p_C1.assign(n, std::nullopt);
  if (n < 5 || normalized2.size() != n || pixels1.size() != n || pixels2.size() != n) {
    result.failure = "fewer than 5 point pairs";
    return result;
  }
  std::vector<cv::Point2d> a(n), b(n);
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = {normalized1[i].x(), normalized1[i].y()};
    b[i] = {normalized2[i].x(), normalized2[i].y()};
  }
  const double focal = 0.5 * (camera.parameters().fx + camera.parameters().fy);
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(a, b, K, cv::RANSAC, 0.999,
                                         options.ransac_threshold_px / focal, mask);
  if (E.empty() || E.rows != 3) {
    result.failure = "no essential matrix";
    return result;
  }
  result.ransac_inliers = cv::countNonZero(mask);
  cv::Mat R, t;
  cv::Mat pose_mask = mask.clone();
  // recoverPose's distance threshold bounds depths in units of the baseline:
  // points farther than 1000 baselines count as at infinity.
  cv::recoverPose(E.rowRange(0, 3), a, b, K, R, t, pose_mask);
  Eigen::Matrix3d R_C2_C1;
  Eigen::Vector3d t_C2_C1;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_C2_C1(r, c) = R.at<double>(r, c);
    t_C2_C1(r) = t.at<double>(r);
  }
  const SE3d T_C2_C1(Eigen::Quaterniond(R_C2_C1).normalized(), t_C2_C1);
  const SE3d T_C1_C2 = T_C2_C1.inverse();

  TriangulationLimits limits;
  limits.min_angle_rad = options.min_point_parallax_rad;
  limits.max_error_px = options.max_error_px;
  std::vector<double> parallaxes, depths;
  int in_front = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask.at<unsigned char>(int(i))) continue;
    const std::vector<TriangulationView> views{{SE3d(), normalized1[i], pixels1[i]},
                                               {T_C1_C2, normalized2[i], pixels2[i]}};
    const TriangulationResult tri = triangulateLandmark(views, camera, limits);
    if (tri.outcome != TriangulationOutcome::behind_camera &&
        tri.outcome != TriangulationOutcome::degenerate) {
      ++in_front;
    }
    if (!tri.ok()) continue;
    result.p_C1[i] = tri.p_F;
    parallaxes.push_back(tri.parallax_rad);
    depths.push_back(tri.p_F.z());
  }
  result.landmarks = static_cast<int>(parallaxes.size());
  const double cheirality = result.ransac_inliers > 0 ? double(in_front) / result.ransac_inliers : 0.0;
  if (result.landmarks < options.min_landmarks) {
    result.failure = describe("landmarks", result.landmarks, options.min_landmarks);
    return result;
  }
  if (cheirality < options.min_cheirality_fraction) {
    result.failure = describe("fraction in front of both cameras", cheirality,
                              options.min_cheirality_fraction);
    return result;
  }
  std::nth_element(parallaxes.begin(), parallaxes.begin() + parallaxes.size() / 2, parallaxes.end());
  result.median_parallax_rad = parallaxes[parallaxes.size() / 2];
  if (result.median_parallax_rad < options.min_parallax_rad) {
    result.failure = describe("median parallax (deg)", result.median_parallax_rad * 180.0 / M_PI,
                              options.min_parallax_rad * 180.0 / M_PI);
    return result;
  }
  SE3d refined_T_C1_C2 = T_C1_C2;
  refineTwoView(pixels1, pixels2, camera, options, refined_T_C1_C2, result.p_C1);
  depths.clear();
  for (const auto& p : result.p_C1) {
    if (p) depths.push_back(p->z());
  }
  if (int(depths.size()) < options.min_landmarks) {
    result.failure = describe("landmarks after refinement", double(depths.size()), options.min_landmarks);
    return result;
  }
  result.landmarks = int(depths.size());
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const double scale = 1.0 / depths[depths.size() / 2];
  for (auto& p : result.p_C1) {
    if (p) *p *= scale;
  }
  result.T_C1_C2 = SE3d(refined_T_C1_C2.q, refined_T_C1_C2.t * scale);
  result.ok = true;
  return result;
}

}  // namespace hsmap
