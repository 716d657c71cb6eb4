#include "pipelines/georef/georef_bundle_adjuster.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/pinhole_radtan_camera.h"
#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/ins_attitude_factor.h"
#include "factors/ins_position_factor.h"
#include "factors/pinhole_intrinsics_prior_factor.h"
#include "factors/reprojection_factor.h"
#include "factors/reprojection_with_intrinsics_factor.h"
#include "solvers/graph_problem.h"
#include "solvers/marginal_covariance.h"

namespace hsmap {
namespace {

SE3d poseOf(const Values& values, int keyframe) {
  const Key key = X(std::uint64_t(keyframe));
  return SE3d(values.poseRotation(key).normalized(), values.poseTranslation(key));
}

// Whitened position residual of each link's fix at the current values.
std::vector<double> whitenedFixResiduals(const Values& values, const std::vector<InsFixLink>& links,
                                         const std::vector<bool>& active, const InsBodyTrack& ins,
                                         const SE3d& T_B_C, const InsNoise& noise,
                                         std::vector<double>* offsets_m) {
  const Eigen::Vector3d sigma(noise.sigma_horizontal_m, noise.sigma_horizontal_m,
                              noise.sigma_depth_m);
  std::vector<double> whitened(links.size(), 0.0);
  if (offsets_m) offsets_m->assign(links.size(), 0.0);
  for (std::size_t i = 0; i < links.size(); ++i) {
    if (!active[i]) continue;
    const SE3d T_W_C = poseOf(values, links[i].keyframe) * links[i].T_K_C;
    const Eigen::Vector3d p_W_B = T_W_C * T_B_C.inverse().t;
    const Eigen::Vector3d error = p_W_B - ins.fixes()[std::size_t(links[i].fix)].p_W_B;
    whitened[i] = error.cwiseQuotient(sigma).norm();
    if (offsets_m) (*offsets_m)[i] = error.norm();
  }
  return whitened;
}

constexpr const char* kIntrinsicNames[PinholeRadtanCamera::kNumIntrinsics] = {
    "fx", "fy", "cx", "cy", "distortion[0]", "distortion[1]", "distortion[2]", "distortion[3]", "distortion[4]"};

PinholeRadtanParameters withIntrinsics(PinholeRadtanParameters camera, const Eigen::VectorXd& k) {
  camera.fx = k[0];
  camera.fy = k[1];
  camera.cx = k[2];
  camera.cy = k[3];
  for (int i = 0; i < 5; ++i) camera.distortion[std::size_t(i)] = k[4 + i];
  return camera;
}

// The intrinsics' 1-sigma from their marginal covariance (over the free
// ones, in order) and the ones the survey cannot separate: a correlation
// above the threshold with another estimated intrinsic, or a 1-sigma hardly
// below the prior's.
void checkIntrinsics(const Eigen::MatrixXd& covariance, const std::array<double, 9>& prior_sigma,
                     const GeorefBundleOptions& options, RgbIntrinsicsEstimate& estimate) {
  std::vector<int> free;
  for (int i = 0; i < PinholeRadtanCamera::kNumIntrinsics; ++i) {
    if (prior_sigma[std::size_t(i)] > 0.0) free.push_back(i);
  }
  for (std::size_t a = 0; a < free.size(); ++a) {
    estimate.sigma[std::size_t(free[a])] = std::sqrt(std::max(0.0, covariance(Eigen::Index(a), Eigen::Index(a))));
  }
  estimate.sigma_known = true;
  for (std::size_t a = 0; a < free.size(); ++a) {
    const int i = free[a];
    double worst = 0.0;
    int worst_other = -1;
    for (std::size_t b = 0; b < free.size(); ++b) {
      if (b == a) continue;
      const double denominator = std::sqrt(std::max(0.0, covariance(Eigen::Index(a), Eigen::Index(a))) *
                                           std::max(0.0, covariance(Eigen::Index(b), Eigen::Index(b))));
      if (!(denominator > 0.0)) continue;
      const double correlation = covariance(Eigen::Index(a), Eigen::Index(b)) / denominator;
      if (std::abs(correlation) > std::abs(worst)) {
        worst = correlation;
        worst_other = free[b];
      }
    }
    const std::string name = std::string("rgb_camera.") + kIntrinsicNames[i];
    std::ostringstream reason;
    if (worst_other >= 0 && std::abs(worst) > options.inseparable_correlation) {
      reason << name << " cannot be separated from rgb_camera." << kIntrinsicNames[worst_other]
             << " on this survey (correlation " << worst << ")";
      estimate.inseparable.push_back(reason.str());
    } else if (estimate.sigma[std::size_t(i)] > options.weak_fraction_of_prior * prior_sigma[std::size_t(i)]) {
      // What it is most likely confounded with, for the reader.
      const char* why = i < 2 ? ": the focal length trades against the distance to the seabed unless relief or "
                                "changes of altitude and attitude separate them"
                      : i < 4 ? ": the image centre trades against the map's horizontal placement, which the INS "
                                "positions fix only to their noise, unless relief or attitude changes separate them"
                              : "";
      reason << name << " is hardly determined by this survey (its 1-sigma " << estimate.sigma[std::size_t(i)]
             << " is more than " << options.weak_fraction_of_prior << " of the prior's "
             << prior_sigma[std::size_t(i)] << why << "); it stays close to survey.yaml's value";
      estimate.inseparable.push_back(reason.str());
    }
  }
}

}  // namespace

std::array<double, 9> rgbIntrinsicsOf(const PinholeRadtanParameters& camera) {
  return {camera.fx, camera.fy, camera.cx, camera.cy, camera.distortion[0], camera.distortion[1],
          camera.distortion[2], camera.distortion[3], camera.distortion[4]};
}

std::array<double, 9> rgbIntrinsicsOf(const PinholeRadtanSigma& sigma) {
  return {sigma.fx, sigma.fy, sigma.cx, sigma.cy, sigma.distortion[0], sigma.distortion[1],
          sigma.distortion[2], sigma.distortion[3], sigma.distortion[4]};
}

GeorefBundleReport adjustGeoreferencedMap(VisualMap& map, const std::vector<InsFixLink>& links,
                                          const InsBodyTrack& ins, const SE3d& T_B_C,
                                          const InsNoise& noise,
                                          const PinholeRadtanParameters& camera,
                                          const GeorefBundleOptions& options,
                                          const std::optional<PinholeRadtanSigma>& intrinsics_sigma) {
  GeorefBundleReport report;
  Values values;
  const bool estimates_intrinsics = intrinsics_sigma && intrinsics_sigma->asksForCalibration();
  const std::array<double, 9> prior_intrinsics = rgbIntrinsicsOf(camera);
  const std::array<double, 9> prior_sigma =
      estimates_intrinsics ? rgbIntrinsicsOf(*intrinsics_sigma) : std::array<double, 9>{};
  GraphProblemOptions problem_options;
  if (estimates_intrinsics) {
    values.insertVector(K(0), Eigen::Map<const Eigen::VectorXd>(prior_intrinsics.data(), 9));
    const std::vector<int> held = PinholeIntrinsicsPriorFactor::heldParameters(prior_sigma);
    if (!held.empty()) problem_options.constant_components[K(0)] = held;
  }
  // With the intrinsics estimated, the last round's problem stays for the covariance.
  std::unique_ptr<FactorGraph> last_graph;
  std::unique_ptr<GraphProblem> last_problem;
  std::set<int> used_keyframes;
  std::vector<int> landmark_ids;
  std::vector<bool> adjusted_landmark(map.landmarks().size(), false);
  for (const Landmark& landmark : map.landmarks()) {
    if (!landmark.valid || landmark.keyframe_ids.size() < 2) continue;
    adjusted_landmark[std::size_t(landmark.id)] = true;
    values.insertPoint(L(std::uint64_t(landmark.id)), landmark.p_F);
    landmark_ids.push_back(landmark.id);
    for (int k : landmark.keyframe_ids) used_keyframes.insert(k);
  }
  for (const InsFixLink& link : links) used_keyframes.insert(link.keyframe);
  for (int k : used_keyframes) {
    values.insertPose(X(std::uint64_t(k)), map.keyframe(k).T_F_C.q, map.keyframe(k).T_F_C.t);
  }
  report.keyframes = int(used_keyframes.size());
  report.attitude_measured = ins.hasAttitude();
  report.position_correlation_factor = noise.position_correlation_factor;
  report.landmarks = int(landmark_ids.size());

  const NoiseModel pixel_noise = NoiseModel::isotropic(2, options.pixel_sigma_px);
  const RobustLoss huber = RobustLoss::huber(options.huber_sigmas);
  const NoiseModel position_noise = NoiseModel::fromSigmas(
      noise.position_correlation_factor *
      Eigen::Vector3d(noise.sigma_horizontal_m, noise.sigma_horizontal_m, noise.sigma_depth_m));
  const NoiseModel attitude_noise = NoiseModel::fromSigmas(
      ins.hasAttitude() ? noise.sigma_attitude_rad
                        : Eigen::Vector3d(noise.assumed_level_sigma_rad, noise.assumed_level_sigma_rad,
                                          noise.assumed_heading_sigma_rad));

  std::vector<bool> active(links.size(), true);
  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_schur;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.num_threads;
  solver.function_tolerance = 1e-7;

  for (int round = 0;; ++round) {
    auto graph_owner = std::make_unique<FactorGraph>();
    FactorGraph& graph = *graph_owner;
    report.reprojection_factors = report.position_factors = report.attitude_factors = 0;
    for (int k : used_keyframes) {
      for (const KeyframeObservation& o : map.keyframe(k).observations) {
        if (!adjusted_landmark[std::size_t(o.landmark_id)]) continue;
        if (estimates_intrinsics) {
          graph.emplace<ReprojectionWithIntrinsicsFactor>(X(std::uint64_t(k)), L(std::uint64_t(o.landmark_id)),
                                                          K(0), o.pixel, pixel_noise, huber);
        } else {
          graph.emplace<ReprojectionFactor>(X(std::uint64_t(k)), L(std::uint64_t(o.landmark_id)),
                                            o.pixel, camera, pixel_noise, huber);
        }
        ++report.reprojection_factors;
      }
    }
    for (std::size_t i = 0; i < links.size(); ++i) {
      if (!active[i]) continue;
      const InsBodyFix& fix = ins.fixes()[std::size_t(links[i].fix)];
      // T_B_K = T_B_C T_C_K: the fix's body pose seen from the keyframe.
      const SE3d T_B_K = T_B_C * links[i].T_K_C.inverse();
      graph.emplace<InsPositionFactor>(X(std::uint64_t(links[i].keyframe)), fix.p_W_B, T_B_K,
                                       position_noise);
      ++report.position_factors;
      graph.emplace<InsAttitudeFactor>(X(std::uint64_t(links[i].keyframe)), fix.q_W_B, T_B_K,
                                       attitude_noise);
      ++report.attitude_factors;
    }
    SolveReport solved;
    if (estimates_intrinsics) {
      graph.emplace<PinholeIntrinsicsPriorFactor>(K(0), prior_intrinsics, prior_sigma);
      last_problem.reset();
      last_problem = std::make_unique<GraphProblem>(graph, values, problem_options);
      last_graph = std::move(graph_owner);
      solved = solve(*last_problem, solver);
    } else {
      solved = solve(graph, values, solver);
    }
    if (round == 0) report.first_solve = solved;
    report.last_solve = solved;
    ++report.solves;
    if (!solved.usable) {
      throw std::runtime_error("the geo-referencing bundle adjustment failed: " + solved.reason +
                               " (" + solved.ceres_message + ")");
    }
    if (round >= options.max_fix_rejection_rounds) break;
    std::vector<double> offsets;
    const std::vector<double> whitened =
        whitenedFixResiduals(values, links, active, ins, T_B_C, noise, &offsets);
    // Reject the local maxima beyond the gate: a faulty fix drags its
    // neighbours' residuals up too, and they recover once it is gone.
    bool rejected_any = false;
    for (std::size_t i = 0; i < links.size(); ++i) {
      if (!active[i] || whitened[i] <= options.fix_gate_sigmas) continue;
      bool local_max = true;
      for (std::size_t j = (i >= 2 ? i - 2 : 0); j <= std::min(links.size() - 1, i + 2); ++j) {
        if (j != i && active[j] && whitened[j] > whitened[i]) local_max = false;
      }
      if (!local_max) continue;
      const InsBodyFix& fix = ins.fixes()[std::size_t(links[i].fix)];
      report.rejected.push_back({links[i].fix, fix.line_number, fix.t, offsets[i], "bundle adjustment"});
      rejected_any = true;
    }
    if (!rejected_any) break;
    for (const RejectedFix& r : report.rejected) {
      for (std::size_t i = 0; i < links.size(); ++i) {
        if (links[i].fix == r.fix) active[i] = false;
      }
    }
  }

  for (int k : used_keyframes) map.keyframe(k).T_F_C = poseOf(values, k);
  for (int l : landmark_ids) map.landmark(l).p_F = values.point(L(std::uint64_t(l)));
  if (estimates_intrinsics) {
    RgbIntrinsicsEstimate estimate;
    estimate.camera = withIntrinsics(camera, values.vector(K(0)));
    const auto start = std::chrono::steady_clock::now();
    try {
      CovarianceOptions covariance_options;
      covariance_options.num_threads = options.num_threads;
      // Only K(0) is asked for: the landmarks go by their Schur complement,
      // the reduced system is the keyframes' poses and K(0).
      covariance_options.algorithm = CovarianceOptions::Algorithm::landmark_schur;
      const Eigen::MatrixXd covariance = jointMarginalCovariance(*last_problem, {K(0)}, covariance_options);
      checkIntrinsics(covariance, prior_sigma, options, estimate);
    } catch (const std::exception& error) {
      estimate.covariance_error = error.what();
    }
    estimate.covariance_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.intrinsics = estimate;
  }
  // Observations the solve left far from their landmark are dropped, so the
  // frames posed against this map next do not meet them.
  const PinholeRadtanCamera lens(report.intrinsics ? report.intrinsics->camera : camera);
  std::vector<std::pair<int, int>> far;  // (keyframe, landmark)
  for (int k : used_keyframes) {
    const Keyframe& keyframe = map.keyframe(k);
    const SE3d T_C_W = keyframe.T_F_C.inverse();
    for (const KeyframeObservation& o : keyframe.observations) {
      if (!adjusted_landmark[std::size_t(o.landmark_id)]) continue;
      const Eigen::Vector3d p_C = T_C_W * map.landmark(o.landmark_id).p_F;
      if (!(p_C.z() > 0.0) || (lens.project(p_C) - o.pixel).norm() > options.outlier_px) {
        far.emplace_back(k, o.landmark_id);
      }
    }
  }
  for (const auto& [k, l] : far) map.removeObservation(k, l);
  report.removed_observations = int(far.size());
  for (int l : landmark_ids) {
    if (map.landmark(l).valid && map.landmark(l).keyframe_ids.size() < 2) map.removeLandmark(l);
  }
  return report;
}

}  // namespace hsmap
