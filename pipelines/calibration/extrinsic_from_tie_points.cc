#include "pipelines/calibration/extrinsic_from_tie_points.h"

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
#include "core/util/median.h"
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
    if (rotation_per_time_offset_deg_s && translation_per_time_offset_m_s) {
      const Eigen::Vector3d& r = *rotation_per_time_offset_deg_s;
      const Eigen::Vector3d& t = *translation_per_time_offset_m_s;
      out << "  T_C_U per ms of the time offset d (kept at the survey's guess): rotation (deg, about U x y z) "
          << fixedDecimals(r[0] / 1000.0, 4) << " " << fixedDecimals(r[1] / 1000.0, 4) << " "
          << fixedDecimals(r[2] / 1000.0, 4) << ", translation (mm, along C x y z) " << fixedDecimals(t[0], 2)
          << " " << fixedDecimals(t[1], 2) << " " << fixedDecimals(t[2], 2) << "; the 1-sigma below includes d's "
          << fixedDecimals(1000.0 * time_offset_sigma_s, 1) << " ms\n";
    }
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
  auto poseAt = [&](double line_position) -> std::optional<SE3d> {
    if (!std::isfinite(line_position)) return std::nullopt;
    const double below = std::floor(line_position);
    const auto a = pose_of_line.find((long long)below);
    if (a == pose_of_line.end()) return std::nullopt;
    const double alpha = line_position - below;
    if (alpha == 0.0) return a->second->T;
    const auto b = pose_of_line.find((long long)below + 1);
    if (b == pose_of_line.end()) return std::nullopt;
    return interpolatePose(a->second->T, b->second->T, alpha);
  };
  for (const ExtrinsicTiePoint& tie : tie_points) {
    const std::optional<SE3d> T_W_U = poseAt(tie.line_position);
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
  // T_W_C of each tie (index as `ties`): the line poses' own, or shifted along the lines.
  auto buildGraphWith = [&](const std::vector<bool>& keep, const std::vector<SE3d>& T_W_C) {
    FactorGraph graph;
    graph.emplace<ExtrinsicPriorFactor>(E(0), prior.T_C_U, prior_noise);
    for (std::size_t i = 0; i < ties.size(); ++i) {
      if (!keep[i]) continue;
      const ExtrinsicTiePoint& tie = *ties[i].tie;
      const double range = tie.range_m > 0.0 ? tie.range_m : kDefaultRangeM;
      const double sigma_across = options.sigma_match_m / range;
      const Eigen::Vector2d sigmas(camera_parameters.f * sigma_across, sigma_across);
      graph.emplace<PushbroomExtrinsicFactor>(E(0), T_W_C[i], tie.p_W, tie.sample,
                                              camera_parameters, NoiseModel::fromSigmas(sigmas),
                                              RobustLoss::cauchy(options.robust_scale));
    }
    return graph;
  };
  std::vector<SE3d> line_T_W_C;
  for (const Tie& tie : ties) line_T_W_C.push_back(tie.T_W_C);
  auto buildGraph = [&](const std::vector<bool>& keep) { return buildGraphWith(keep, line_T_W_C); };

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

  // What d's uncertainty adds (see the header): the solve again with the
  // tie points' line poses +-delta along the lines.
  if (prior.time_offset_sigma_s > 0.0 && result.sigma_rotation_deg && result.sigma_translation_m) {
    result.time_offset_sigma_s = prior.time_offset_sigma_s;
    std::vector<double> periods;  // seconds per line, between consecutive posed lines
    for (const LinePose& pose : line_poses) {
      const auto next = pose_of_line.find(pose.line + 1);
      if (next != pose_of_line.end()) periods.push_back(next->second->t - pose.t);
    }
    const double period = upperMedian(periods);
    constexpr double kDelta = 0.005;  // s: T_C_U moves linearly with d over this
    std::optional<SE3d> shifted_solution[2];
    if (period > 0.0) {
      std::vector<bool> keep_shifted = keep;
      std::vector<SE3d> T_W_C[2] = {line_T_W_C, line_T_W_C};
      for (std::size_t i = 0; i < ties.size(); ++i) {
        if (!keep_shifted[i]) continue;
        for (int side = 0; side < 2; ++side) {
          const double shift_lines = (side == 0 ? -kDelta : kDelta) / period;
          const std::optional<SE3d> T_W_U = poseAt(ties[i].tie->line_position + shift_lines);
          if (!T_W_U) {
            keep_shifted[i] = false;  // near the ends: out of both shifted solves
            break;
          }
          T_W_C[side][i] = *T_W_U * T_U_C_lines;
        }
      }
      for (int side = 0; side < 2; ++side) {
        Values shifted_values;
        shifted_values.insertPose(E(0), result.T_C_U.q, result.T_C_U.t);
        const FactorGraph shifted_graph = buildGraphWith(keep_shifted, T_W_C[side]);
        GraphProblem shifted_problem(shifted_graph, shifted_values);
        if (solve(shifted_problem, solver).usable) {
          shifted_solution[side] =
              SE3d(shifted_values.poseRotation(E(0)).normalized(), shifted_values.poseTranslation(E(0)));
        }
      }
    }
    if (shifted_solution[0] && shifted_solution[1]) {
      const SE3d& minus = *shifted_solution[0];
      const SE3d& plus = *shifted_solution[1];
      const Eigen::AngleAxisd turn(minus.q.conjugate() * plus.q);  // about U's axes
      const Eigen::Vector3d rotation_deg_s = turn.angle() * turn.axis() * (180.0 / std::numbers::pi) / (2.0 * kDelta);
      const Eigen::Vector3d translation_m_s = (plus.t - minus.t) / (2.0 * kDelta);
      result.rotation_per_time_offset_deg_s = rotation_deg_s;
      result.translation_per_time_offset_m_s = translation_m_s;
      const double sd = prior.time_offset_sigma_s;
      result.sigma_rotation_deg = (result.sigma_rotation_deg->array().square() +
                                   (rotation_deg_s.array() * sd).square()).sqrt().matrix();
      result.sigma_translation_m = (result.sigma_translation_m->array().square() +
                                    (translation_m_s.array() * sd).square()).sqrt().matrix();
    } else {
      result.warnings.push_back(
          "the 1-sigma leaves out the time offset's uncertainty (the shifted solves failed)");
    }
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
