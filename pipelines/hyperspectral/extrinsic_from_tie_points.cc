#include "pipelines/hyperspectral/extrinsic_from_tie_points.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <exception>
#include <numbers>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/graph/factor_graph.h"
#include "core/graph/key.h"
#include "core/graph/values.h"
#include "core/util/message_text.h"
#include "factors/extrinsic_prior_factor.h"
#include "factors/pushbroom_extrinsic_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/graph_solver.h"
#include "solvers/marginal_covariance.h"
#include "solvers/robust_outliers.h"

namespace hsmap {

namespace {

constexpr double kDefaultRangeM = 2.0;

struct LineResidual {
  double u = 0.0;       // px
  double across = 0.0;  // px (f * y / z)
};

LineResidual lineResidual(const PushbroomCamera& camera, const SE3d& T_W_C, const SE3d& T_C_U,
                          const Eigen::Vector3d& p_W, double sample) {
  const Eigen::Vector3d p_U = (T_W_C * T_C_U).inverse() * p_W;
  const Eigen::Vector2d projected = camera.project(p_U);
  return {projected.x() - sample, camera.parameters().f * projected.y()};
}

// Rotation (deg) and translation (m) of T_a^-1 T_b, for the log.
Eigen::Vector2d extrinsicChange(const SE3d& a, const SE3d& b) {
  const double angle = 2.0 * std::acos(std::min(1.0, std::abs(a.q.dot(b.q))));
  return {angle * 180.0 / std::numbers::pi, (b.t - a.t).norm()};
}

}  // namespace

std::string ExtrinsicRefinementResult::summary() const {
  std::ostringstream out;
  out << "extrinsic refinement: " << patches << " patches, " << matches << " matches, "
      << tie_points << " tie points, " << inliers << " inliers, " << outliers
      << " outliers; median shift " << fixedDecimals(1000.0 * median_shift_m, 1) << " mm";
  if (band_fit_r2 > 0.0) out << "; band fit R^2 " << fixedDecimals(band_fit_r2, 3);
  out << "\n";
  if (!refined) {
    out << "  T_C_U kept (not refined)\n";
  } else {
    const Eigen::Vector2d change = extrinsicChange(T_C_U_initial, T_C_U);
    out << "  T_C_U moved by " << fixedDecimals(change.x(), 3) << " deg, " << fixedDecimals(1000.0 * change.y(), 1)
        << " mm; residual RMS u " << fixedDecimals(rms_u_before_px, 2) << " -> " << fixedDecimals(rms_u_after_px, 2)
        << " px, across " << fixedDecimals(rms_across_before_px, 2) << " -> "
        << fixedDecimals(rms_across_after_px, 2) << " px\n";
    if (sigma_rotation_deg && sigma_translation_m) {
      out << "  1-sigma rotation (deg, about U x y z) " << fixedDecimals((*sigma_rotation_deg)[0], 4) << " "
          << fixedDecimals((*sigma_rotation_deg)[1], 4) << " " << fixedDecimals((*sigma_rotation_deg)[2], 4)
          << ", translation (mm, along C x y z) " << fixedDecimals(1000.0 * (*sigma_translation_m)[0], 2)
          << " " << fixedDecimals(1000.0 * (*sigma_translation_m)[1], 2) << " "
          << fixedDecimals(1000.0 * (*sigma_translation_m)[2], 2) << "\n";
    }
  }
  for (const std::string& warning : warnings) out << "  warning: " << warning << "\n";
  return out.str();
}

ExtrinsicRefinementResult refineExtrinsicFromTiePoints(
    const std::vector<ExtrinsicTiePoint>& tie_points, const std::vector<LinePose>& line_poses,
    const SE3d& T_C_U_lines, const PushbroomParameters& camera_parameters,
    const ExtrinsicPrior& prior, const ExtrinsicRefinementOptions& options) {
  options.validate();
  const PushbroomCamera camera(camera_parameters);
  ExtrinsicRefinementResult result;
  result.T_C_U_initial = T_C_U_lines;
  result.T_C_U = T_C_U_lines;
  result.tie_points = std::int64_t(tie_points.size());

  std::unordered_map<long long, const LinePose*> pose_of_line;
  for (const LinePose& pose : line_poses) pose_of_line[pose.line] = &pose;
  const SE3d T_U_C_lines = T_C_U_lines.inverse();

  // The usable tie points and their line camera poses.
  struct Tie {
    const ExtrinsicTiePoint* tie;
    SE3d T_W_C;
  };
  std::vector<Tie> ties;
  std::int64_t without_line = 0;
  // The UHI pose at the tie's continuous line position, interpolated between
  // the two lines around it (both must be posed).
  auto poseAt = [&](const ExtrinsicTiePoint& tie) -> std::optional<SE3d> {
    if (!std::isfinite(tie.line_position)) return std::nullopt;
    const double below = std::floor(tie.line_position);
    const auto a = pose_of_line.find((long long)below);
    if (a == pose_of_line.end()) return std::nullopt;
    const double alpha = tie.line_position - below;
    if (alpha == 0.0) return a->second->T;
    const auto b = pose_of_line.find((long long)below + 1);
    if (b == pose_of_line.end()) return std::nullopt;
    return interpolatePose(a->second->T, b->second->T, alpha);
  };
  for (const ExtrinsicTiePoint& tie : tie_points) {
    const std::optional<SE3d> T_W_U = poseAt(tie);
    if (!T_W_U || !tie.p_W.allFinite() || !std::isfinite(tie.sample)) {
      ++without_line;
      continue;
    }
    ties.push_back({&tie, *T_W_U * T_U_C_lines});
  }
  if (without_line > 0) {
    result.warnings.push_back(std::to_string(without_line) +
                              " tie points skipped: line without pose or non-finite values");
  }
  if (int(ties.size()) < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(ties.size()) + " usable tie points (< " +
                              std::to_string(options.min_tie_points) +
                              "): T_C_U kept at the line poses' extrinsic (the prior alone "
                              "cannot improve it)");
    return result;
  }

  const NoiseModel prior_noise =
      ExtrinsicPriorFactor::noiseFromSigmas(prior.sigma_rotation_deg, prior.sigma_translation_m);
  auto buildGraph = [&](const std::vector<bool>& keep) {
    FactorGraph graph;
    graph.emplace<ExtrinsicPriorFactor>(E(0), prior.T_C_U, prior_noise);
    for (std::size_t i = 0; i < ties.size(); ++i) {
      if (!keep[i]) continue;
      const ExtrinsicTiePoint& tie = *ties[i].tie;
      const double range = tie.range_m > 0.0 ? tie.range_m : kDefaultRangeM;
      const double sigma_across = options.sigma_match_m / range;
      const Eigen::Vector2d sigmas(camera_parameters.f * sigma_across, sigma_across);
      graph.emplace<PushbroomExtrinsicFactor>(E(0), ties[i].T_W_C, tie.p_W, tie.sample,
                                              camera_parameters, NoiseModel::fromSigmas(sigmas),
                                              RobustLoss::cauchy(options.robust_scale));
    }
    return graph;
  };

  Values values;
  values.insertPose(E(0), T_C_U_lines.q, T_C_U_lines.t);
  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_normal_cholesky;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;

  // First solve with every tie point; the factors beyond the loss scale are outliers.
  std::vector<bool> keep(ties.size(), true);
  {
    const FactorGraph graph = buildGraph(keep);
    GraphProblem problem(graph, values);
    solve(problem, solver);
    for (const std::size_t index : factorsBeyondLossScale(problem)) {
      keep[index - 1] = false;  // factor 0 is the prior
      ++result.outliers;
    }
  }
  result.inliers = std::int64_t(std::count(keep.begin(), keep.end(), true));
  if (result.inliers < options.min_tie_points) {
    result.warnings.push_back("only " + std::to_string(result.inliers) +
                              " inliers: T_C_U kept at the line poses' extrinsic");
    return result;
  }
  // Final solve on the inliers, from the first solve's estimate.
  const FactorGraph graph = buildGraph(keep);
  GraphProblem problem(graph, values);
  const SolveReport report = solve(problem, solver);
  result.solve_report = report.toString();
  if (!report.usable) {
    result.warnings.push_back("the solve failed: T_C_U kept (" + report.reason + ")");
    return result;
  }
  result.T_C_U = SE3d(values.poseRotation(E(0)).normalized(), values.poseTranslation(E(0)));
  result.refined = true;
  try {
    CovarianceOptions covariance_options;
    covariance_options.algorithm = CovarianceOptions::Algorithm::dense_svd;
    const Eigen::MatrixXd covariance =
        marginalCovariances(problem, {E(0)}, covariance_options).at(E(0));
    const Eigen::Matrix3d R_C_U = result.T_C_U.q.toRotationMatrix();
    const Eigen::Matrix3d translation_C =
        R_C_U * covariance.topLeftCorner<3, 3>() * R_C_U.transpose();
    result.sigma_translation_m = translation_C.diagonal().cwiseMax(0.0).cwiseSqrt();
    result.sigma_rotation_deg =
        Eigen::Vector3d(covariance.bottomRightCorner<3, 3>().diagonal().cwiseMax(0.0).cwiseSqrt() *
                        (180.0 / std::numbers::pi));
  } catch (const std::exception& error) {
    result.warnings.push_back(std::string("no covariance: ") + error.what());
  }

  // Residual RMS over the inliers, before and after.
  double su0 = 0, sa0 = 0, su1 = 0, sa1 = 0;
  for (std::size_t i = 0; i < ties.size(); ++i) {
    if (!keep[i]) continue;
    const ExtrinsicTiePoint& tie = *ties[i].tie;
    const LineResidual before =
        lineResidual(camera, ties[i].T_W_C, T_C_U_lines, tie.p_W, tie.sample);
    const LineResidual after =
        lineResidual(camera, ties[i].T_W_C, result.T_C_U, tie.p_W, tie.sample);
    su0 += before.u * before.u;
    sa0 += before.across * before.across;
    su1 += after.u * after.u;
    sa1 += after.across * after.across;
    result.used.push_back(tie);
  }
  const double n = double(result.inliers);
  result.rms_u_before_px = std::sqrt(su0 / n);
  result.rms_across_before_px = std::sqrt(sa0 / n);
  result.rms_u_after_px = std::sqrt(su1 / n);
  result.rms_across_after_px = std::sqrt(sa1 / n);
  return result;
}

}  // namespace hsmap
