#include "pipelines/frontend/local_bundle_adjuster.h"

#include <algorithm>
#include <set>

#include "core/graph/factor_graph.h"
#include "core/graph/values.h"
#include "factors/reprojection_factor.h"
#include "solvers/graph_solver.h"

namespace hsmap {

std::pair<int, int> removeOutlierObservations(VisualMap& map, const std::vector<int>& landmark_ids,
                                              const PinholeRadtanCamera& camera, double outlier_px) {
  int removed_observations = 0, removed_landmarks = 0;
  for (int l : landmark_ids) {
    Landmark& landmark = map.landmark(l);
    if (!landmark.valid) continue;
    const std::vector<int> observers = landmark.keyframe_ids;
    for (int k : observers) {
      const Keyframe& keyframe = map.keyframe(k);
      const auto it = std::find_if(keyframe.observations.begin(), keyframe.observations.end(),
                                   [&](const KeyframeObservation& o) { return o.landmark_id == l; });
      const Eigen::Vector3d p_C = keyframe.T_F_C.inverse() * landmark.p_F;
      const bool bad = !(p_C.z() > 0.0) || (camera.project(p_C) - it->pixel).norm() > outlier_px;
      if (bad) {
        map.removeObservation(k, l);
        ++removed_observations;
      }
    }
    if (landmark.keyframe_ids.size() < 2) {
      map.removeLandmark(l);
      ++removed_landmarks;
    }
  }
  return {removed_observations, removed_landmarks};
}

namespace {

// The solve of both entry points: free and fixed keyframes, and the landmarks
// to adjust (those with two observations among the keyframes are kept).
LocalBundleAdjustmentReport adjustSets(VisualMap& map, const std::set<int>& free_set,
                                       const std::set<int>& fixed_set, const std::set<int>& landmark_set,
                                       const PinholeRadtanCamera& camera,
                                       const LocalBundleAdjustmentOptions& options) {
  LocalBundleAdjustmentReport report;
  if (free_set.empty()) return report;

  FactorGraph graph;
  Values values;
  std::set<Key> constant;
  const NoiseModel noise = NoiseModel::isotropic(2, options.pixel_sigma_px);
  const RobustLoss loss = RobustLoss::huber(options.huber_scale);
  auto addPose = [&](int k, bool fixed_pose) {
    const Keyframe& kf = map.keyframe(k);
    values.insertPose(X(std::uint64_t(k)), kf.T_F_C.q, kf.T_F_C.t);
    if (fixed_pose) constant.insert(X(std::uint64_t(k)));
  };
  for (int k : free_set) addPose(k, false);
  for (int k : fixed_set) addPose(k, true);
  std::vector<int> landmark_ids;
  std::set<int> accepted;
  for (int l : landmark_set) {
    const Landmark& landmark = map.landmark(l);
    int observations = 0;
    for (int k : landmark.keyframe_ids) observations += (free_set.count(k) || fixed_set.count(k)) ? 1 : 0;
    if (observations < 2) continue;  // a single view cannot place it
    values.insertPoint(L(std::uint64_t(l)), landmark.p_F);
    landmark_ids.push_back(l);
    accepted.insert(l);
  }
  for (const std::set<int>* keyframes : {&free_set, &fixed_set}) {
    for (int k : *keyframes) {
      for (const auto& o : map.keyframe(k).observations) {
        if (!accepted.count(o.landmark_id)) continue;
        graph.emplace<ReprojectionFactor>(X(std::uint64_t(k)), L(std::uint64_t(o.landmark_id)),
                                          o.pixel, camera.parameters(), noise, loss);
        ++report.observations;
      }
    }
  }
  if (landmark_ids.empty()) return report;
  report.free_keyframes = int(free_set.size());
  report.fixed_keyframes = int(fixed_set.size());
  report.landmarks = int(landmark_ids.size());

  SolverOptions solver;
  solver.linear_solver = SolverOptions::LinearSolver::sparse_schur;
  solver.max_iterations = options.max_iterations;
  solver.num_threads = options.solver_threads;
  solver.function_tolerance = 1e-5;
  const SolveReport solved = solve(graph, values, solver, constant);
  report.initial_cost = solved.initial_cost;
  report.final_cost = solved.final_cost;
  report.usable = solved.usable;
  if (!solved.usable) return report;
  for (int k : free_set) {
    map.keyframe(k).T_F_C =
        SE3d(values.poseRotation(X(std::uint64_t(k))).normalized(), values.poseTranslation(X(std::uint64_t(k))));
  }
  for (int l : landmark_ids) map.landmark(l).p_F = values.point(L(std::uint64_t(l)));
  const auto [observations, landmarks] =
      removeOutlierObservations(map, landmark_ids, camera, options.outlier_px);
  report.removed_observations = observations;
  report.removed_landmarks = landmarks;
  return report;
}

}  // namespace

LocalBundleAdjustmentReport adjustKeyframes(VisualMap& map, const std::vector<int>& free_keyframes,
                                            const std::vector<int>& fixed_keyframes,
                                            const PinholeRadtanCamera& camera,
                                            const LocalBundleAdjustmentOptions& options) {
  const std::set<int> free_set(free_keyframes.begin(), free_keyframes.end());
  std::set<int> fixed_set(fixed_keyframes.begin(), fixed_keyframes.end());
  for (int k : free_set) fixed_set.erase(k);
  std::set<int> landmark_set;
  for (int k : free_set) {
    for (const auto& o : map.keyframe(k).observations) {
      if (map.landmark(o.landmark_id).valid) landmark_set.insert(o.landmark_id);
    }
  }
  return adjustSets(map, free_set, fixed_set, landmark_set, camera, options);
}

LocalBundleAdjustmentReport adjustLocalWindow(VisualMap& map, const std::vector<int>& window,
                                              const PinholeRadtanCamera& camera,
                                              const LocalBundleAdjustmentOptions& options) {
  LocalBundleAdjustmentReport report;
  if (window.empty()) return report;
  const std::set<int> free_keyframes(window.begin(), window.end());

  // Landmarks seen by the window, and the older keyframes that also see them
  // (counted by how many of those landmarks they see).
  std::set<int> landmark_set;
  for (int k : window) {
    for (const auto& o : map.keyframe(k).observations) {
      if (map.landmark(o.landmark_id).valid) landmark_set.insert(o.landmark_id);
    }
  }
  std::set<int> outside;
  for (int l : landmark_set) {
    for (int k : map.landmark(l).keyframe_ids) {
      if (!free_keyframes.count(k)) outside.insert(k);
    }
  }
  // The newest outside keyframes anchor the window best (they share the most).
  std::vector<int> fixed(outside.rbegin(), outside.rend());
  if (int(fixed.size()) > options.max_fixed_keyframes) fixed.resize(std::size_t(options.max_fixed_keyframes));
  std::set<int> fixed_set(fixed.begin(), fixed.end());
  std::set<int> free_set = free_keyframes;
  if (fixed_set.empty()) {
    // The window reaches the segment's start: hold its first two keyframes.
    std::vector<int> segment_keyframes(free_set.begin(), free_set.end());
    for (std::size_t i = 0; i < segment_keyframes.size() && i < 2; ++i) {
      fixed_set.insert(segment_keyframes[i]);
      free_set.erase(segment_keyframes[i]);
    }
  }
  return adjustSets(map, free_set, fixed_set, landmark_set, camera, options);
}

}  // namespace hsmap

