#include "pipelines/frontend/frame_pose_estimator.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/reprojection_factor.h"
#include "solvers/graph_solver.h"

namespace hsmap {

namespace {

SE3d poseFromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  // OpenCV returns T_C_F (maps F points into the camera).
  const Eigen::Vector3d omega(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  const Eigen::Vector3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return SE3d(expSO3(omega), t).inverse();
}

void rvecTvecFromPose(const SE3d& T_F_C, cv::Mat& rvec, cv::Mat& tvec) {
  const SE3d T_C_F = T_F_C.inverse();
  const Eigen::Vector3d omega = logSO3(T_C_F.q);
  rvec = (cv::Mat_<double>(3, 1) << omega.x(), omega.y(), omega.z());
  tvec = (cv::Mat_<double>(3, 1) << T_C_F.t.x(), T_C_F.t.y(), T_C_F.t.z());
}

}  // namespace

bool refinePoseMotionOnly(const std::vector<PoseCorrespondence>& correspondences,
                          const std::vector<bool>& use, const PinholeRadtanCamera& camera,
                          const PoseEstimatorOptions& options, SE3d& T_F_C) {
  FactorGraph graph;
  Values values;
  std::set<Key> constant;
  const NoiseModel noise = NoiseModel::isotropic(2, options.pixel_sigma_px);
  const RobustLoss loss = RobustLoss::huber(options.huber_scale);
  values.insertPose(X(0), T_F_C.q, T_F_C.t);
  // Six degrees of freedom need far fewer than the few hundred tracks a
  // frame has; an even subsample keeps the cost of the solve (one factor
  // object per correspondence) small at no visible loss of precision.
  const std::size_t used = std::size_t(std::count(use.begin(), use.end(), true));
  const std::size_t stride = std::max<std::size_t>(1, (used + options.max_refined_points - 1) /
                                                          std::size_t(options.max_refined_points));
  std::size_t seen = 0;
  for (std::size_t i = 0; i < correspondences.size(); ++i) {
    if (!use[i]) continue;
    if (seen++ % stride != 0) continue;
    values.insertPoint(L(i), correspondences[i].p_F);
    constant.insert(L(i));
    graph.emplace<ReprojectionFactor>(X(0), L(i), correspondences[i].pixel, camera.parameters(),
                                      noise, loss);
  }
  if (graph.size() < 3) return false;
  SolverOptions solver;
  // One pose: the normal equations are 6x6, no landmark to eliminate.
  solver.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  solver.max_iterations = options.max_iterations;
  solver.function_tolerance = 1e-8;
  solver.num_threads = options.solver_threads;
  const SolveReport report = solve(graph, values, solver, constant);
  if (!report.usable) return false;
  T_F_C = SE3d(values.poseRotation(X(0)).normalized(), values.poseTranslation(X(0)));
  return true;
}

PoseEstimate estimateFramePose(const std::vector<PoseCorrespondence>& correspondences,
                               const SE3d& prediction_T_F_C, const PinholeRadtanCamera& camera,
                               const PoseEstimatorOptions& options) {
  PoseEstimate estimate;
  const std::size_t n = correspondences.size();
  estimate.inliers.assign(n, false);
  if (int(n) < std::max(options.min_inliers, 6)) {
    estimate.failure = "too few landmarks tracked (" + std::to_string(n) + ")";
    return estimate;
  }
  std::vector<cv::Point3d> object(n);
  std::vector<cv::Point2d> image(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& c = correspondences[i];
    object[i] = {c.p_F.x(), c.p_F.y(), c.p_F.z()};
    image[i] = {c.normalized.x(), c.normalized.y()};
  }
  const double focal = 0.5 * (camera.parameters().fx + camera.parameters().fy);
  cv::Mat rvec, tvec;
  rvecTvecFromPose(prediction_T_F_C, rvec, tvec);
  std::vector<int> ransac_inliers;
  const bool found = cv::solvePnPRansac(object, image, cv::Mat::eye(3, 3, CV_64F), cv::noArray(),
                                        rvec, tvec, false, options.ransac_iterations,
                                        float(options.ransac_threshold_px / focal), 0.99,
                                        ransac_inliers, cv::SOLVEPNP_AP3P);
  std::vector<bool> use(n, false);
  SE3d T_F_C = prediction_T_F_C;
  if (found && int(ransac_inliers.size()) >= options.min_inliers) {
    T_F_C = poseFromRvecTvec(rvec, tvec);
    for (int i : ransac_inliers) use[std::size_t(i)] = true;
    estimate.ransac_inliers = int(ransac_inliers.size());
  } else {
    // RANSAC found no consensus; the prediction still may: take the
    // correspondences it explains within a loose threshold.
    const SE3d T_C_F = prediction_T_F_C.inverse();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p_C = T_C_F * correspondences[i].p_F;
      use[i] = p_C.z() > 0.0 &&
               (camera.project(p_C) - correspondences[i].pixel).norm() < 4.0 * options.ransac_threshold_px;
    }
  }
  if (std::count(use.begin(), use.end(), true) < options.min_inliers) {
    estimate.failure = "PnP RANSAC found " + std::to_string(ransac_inliers.size()) +
                       " inliers of " + std::to_string(n);
    return estimate;
  }
  if (!refinePoseMotionOnly(correspondences, use, camera, options, T_F_C)) {
    estimate.failure = "motion-only refinement failed";
    return estimate;
  }
  const SE3d T_C_F = T_F_C.inverse();
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p_C = T_C_F * correspondences[i].p_F;
    if (!(p_C.z() > 0.0)) continue;
    const double e = (camera.project(p_C) - correspondences[i].pixel).norm();
    if (e <= options.inlier_threshold_px) {
      estimate.inliers[i] = true;
      ++estimate.inlier_count;
      sum_sq += e * e;
    }
  }
  estimate.T_F_C = T_F_C;
  if (estimate.inlier_count < options.min_inliers) {
    estimate.failure = "only " + std::to_string(estimate.inlier_count) +
                       " inliers after the motion-only refinement";
    return estimate;
  }
  estimate.rms_error_px = std::sqrt(sum_sq / estimate.inlier_count);
  estimate.ok = true;
  return estimate;
}

}  // namespace hsmap
