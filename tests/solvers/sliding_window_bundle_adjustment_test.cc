// Sliding-window bundle adjustment, the front-end's local BA: the oldest
// keyframes of the window held constant (they fix the gauge, scale included,
// without any INS), the newer ones and the landmarks free. Checked with
// exact pixels, so the solve must land on the truth: constant poses are not
// touched, landmarks seen only by constant keyframes are triangulated, keys
// outside the window may be named constant, and the corner cases (every
// pose constant, every landmark constant, a landmark seen once) stay
// usable. dense_schur, the preset for such windows, reaches the optimum of
// sparse_schur.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "factors/reprojection_factor.h"
#include "solvers/graph_solver.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

constexpr int kWindowEnd = 12;      // keyframes [0, 12) are in the window
constexpr int kFirstFree = 4;       // keyframes [0, 4) are held constant
constexpr int kNumKeyframes = 20;   // the map holds 20 keyframes

// The window's graph on the transect, with exact pixels (the projection of
// the true landmark by the true pose) and the landmarks seen at least twice
// in the window. Values: constant keyframes at the truth, free ones and the
// landmarks at the perturbed start; keyframes after the window are in the
// Values (the map) but in no factor.
struct Window {
  test::Transect transect;
  FactorGraph graph;
  Values values;
  std::set<Key> constant;               // every keyframe not free, in the window or not
  std::vector<int> landmarks;           // in the window
  std::vector<int> only_constant_views; // landmarks seen by constant keyframes only
};

Window makeWindow() {
  test::TransectConfig config;
  config.seed = 3;
  config.num_keyframes = kNumKeyframes;
  config.num_landmarks = 400;
  Window window{test::makeTransect(config), {}, {}, {}, {}, {}};
  const test::Transect& transect = window.transect;
  const PinholeRadtanCamera camera(transect.camera);

  std::map<int, std::vector<int>> views;  // landmark -> keyframes in the window
  for (const test::PixelObservation& observation : transect.observations) {
    if (observation.keyframe < kWindowEnd) views[observation.landmark].push_back(observation.keyframe);
  }
  const NoiseModel pixel_noise = NoiseModel::isotropic(2, 0.5);
  for (const auto& [landmark, keyframes] : views) {
    if (keyframes.size() < 2) continue;
    window.landmarks.push_back(landmark);
    if (keyframes.back() < kFirstFree) window.only_constant_views.push_back(landmark);
    for (const int k : keyframes) {
      const Eigen::Vector2d pixel =
          camera.project(Eigen::Vector3d(transect.T_W_C[k].inverse() * transect.p_W[landmark]));
      window.graph.emplace<ReprojectionFactor>(X(k), L(landmark), pixel, transect.camera,
                                               pixel_noise);
    }
    window.values.insertPoint(L(landmark), transect.start_p_W[landmark]);
  }
  for (int k = 0; k < kNumKeyframes; ++k) {
    const bool free = k >= kFirstFree && k < kWindowEnd;
    const SE3d& T_W_C = free ? transect.start_T_W_C[k] : transect.T_W_C[k];
    window.values.insertPose(X(k), T_W_C.q, T_W_C.t);
    if (!free) window.constant.insert(X(k));
  }
  return window;
}

SolverOptions tightOptions(SolverOptions::LinearSolver solver) {
  SolverOptions options;
  options.linear_solver = solver;
  options.function_tolerance = 1e-14;
  options.gradient_tolerance = 1e-14;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 2;
  return options;
}

double maxPoseError(const Window& window, const Values& values, int first, int end) {
  double worst = 0.0;
  for (int k = first; k < end; ++k) {
    const SE3d estimate(values.poseRotation(X(k)), values.poseTranslation(X(k)));
    worst = std::max(worst, (window.transect.T_W_C[k].inverse() * estimate).log().norm());
  }
  return worst;
}

double maxLandmarkError(const Window& window, const Values& values, const std::vector<int>& which) {
  double worst = 0.0;
  for (const int i : which) {
    worst = std::max(worst, (values.point(L(i)) - window.transect.p_W[i]).norm());
  }
  return worst;
}

void expectPosesUnchanged(const Values& values, const Values& start, int first, int end) {
  for (int k = first; k < end; ++k) {
    EXPECT_EQ(values.poseRotation(X(k)).coeffs(), start.poseRotation(X(k)).coeffs()) << k;
    EXPECT_EQ(values.poseTranslation(X(k)), start.poseTranslation(X(k))) << k;
  }
}

class SlidingWindowTest : public ::testing::TestWithParam<SolverOptions::LinearSolver> {};

TEST_P(SlidingWindowTest, ConstantKeyframesFixTheGaugeAndTheWindowLandsOnTheTruth) {
  const Window window = makeWindow();
  ASSERT_GT(window.landmarks.size(), 200u);
  ASSERT_GT(window.only_constant_views.size(), 5u);
  Values values = window.values;
  ASSERT_GT(maxPoseError(window, values, kFirstFree, kWindowEnd), 0.05);

  const SolveReport report = solve(window.graph, values, tightOptions(GetParam()), window.constant);
  EXPECT_TRUE(report.converged) << report.toString();
  // Only the window's constant keyframes are variables of the problem; the
  // constant keys after the window have no factor and are left out.
  EXPECT_EQ(report.num_constant_variables, static_cast<std::size_t>(kFirstFree));
  EXPECT_EQ(report.num_variables, kWindowEnd + window.landmarks.size());
  EXPECT_EQ(report.num_eliminated_landmarks, window.landmarks.size());
  EXPECT_EQ(report.num_free_parameters,
            6 * (kWindowEnd - kFirstFree) + 3 * static_cast<int>(window.landmarks.size()));

  expectPosesUnchanged(values, window.values, 0, kFirstFree);
  expectPosesUnchanged(values, window.values, kWindowEnd, kNumKeyframes);
  EXPECT_LT(maxPoseError(window, values, kFirstFree, kWindowEnd), 1e-7) << report.toString();
  EXPECT_LT(maxLandmarkError(window, values, window.landmarks), 1e-6);
  EXPECT_LT(maxLandmarkError(window, values, window.only_constant_views), 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Presets, SlidingWindowTest,
                         ::testing::Values(SolverOptions::LinearSolver::sparse_schur,
                                           SolverOptions::LinearSolver::dense_schur),
                         [](const auto& info) { return std::string(toString(info.param)); });

// A small local BA with noisy pixels: both Schur presets reach the same
// optimum (noise makes it a non-trivial one, different from the truth).
TEST(SlidingWindow, DenseSchurReachesTheSparseSchurOptimum) {
  Window window = makeWindow();
  FactorGraph noisy;
  const NoiseModel pixel_noise = NoiseModel::isotropic(2, window.transect.config.pixel_sigma);
  for (const test::PixelObservation& observation : window.transect.observations) {
    if (observation.keyframe >= kWindowEnd || !window.values.contains(L(observation.landmark))) {
      continue;
    }
    noisy.emplace<ReprojectionFactor>(X(observation.keyframe), L(observation.landmark),
                                      observation.pixel, window.transect.camera, pixel_noise,
                                      RobustLoss::huber(2.0));
  }
  std::map<SolverOptions::LinearSolver, Values> solved;
  std::map<SolverOptions::LinearSolver, SolveReport> reports;
  for (const auto solver : {SolverOptions::LinearSolver::sparse_schur,
                            SolverOptions::LinearSolver::dense_schur}) {
    Values values = window.values;
    const auto start = std::chrono::steady_clock::now();
    reports[solver] = solve(noisy, values, tightOptions(solver), window.constant);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %zu factors, %zu landmarks, %d iterations, %.1f ms (linear solver %.1f ms)\n",
                toString(solver), noisy.size(), window.landmarks.size(),
                reports[solver].iterations, 1e3 * seconds, 1e3 * reports[solver].linear_solver_s);
    EXPECT_TRUE(reports[solver].converged) << reports[solver].toString();
    solved.emplace(solver, std::move(values));
  }
  EXPECT_EQ(reports[SolverOptions::LinearSolver::dense_schur].linear_solver, "DENSE_SCHUR (Eigen)");
  const Values& sparse = solved.at(SolverOptions::LinearSolver::sparse_schur);
  const Values& dense = solved.at(SolverOptions::LinearSolver::dense_schur);
  EXPECT_NEAR(reports[SolverOptions::LinearSolver::dense_schur].final_cost,
              reports[SolverOptions::LinearSolver::sparse_schur].final_cost,
              1e-9 * reports[SolverOptions::LinearSolver::sparse_schur].final_cost);
  double worst = 0.0;
  for (int k = kFirstFree; k < kWindowEnd; ++k) {
    const SE3d a(sparse.poseRotation(X(k)), sparse.poseTranslation(X(k)));
    const SE3d b(dense.poseRotation(X(k)), dense.poseTranslation(X(k)));
    worst = std::max(worst, (a.inverse() * b).log().norm());
  }
  for (const int i : window.landmarks) worst = std::max(worst, (sparse.point(L(i)) - dense.point(L(i))).norm());
  EXPECT_LT(worst, 1e-7);
  // ...and the optimum is not the truth (the noise is real).
  EXPECT_GT(maxPoseError(window, dense, kFirstFree, kWindowEnd), 1e-5);
}

// Every pose constant (structure-only BA): only landmarks are free, so the
// reduced camera system is empty.
TEST_P(SlidingWindowTest, EveryPoseConstantTriangulatesTheLandmarks) {
  const Window window = makeWindow();
  Values values = window.values;
  for (int k = kFirstFree; k < kWindowEnd; ++k) {
    values.updatePose(X(k), window.transect.T_W_C[k].q, window.transect.T_W_C[k].t);
  }
  const Values start = values;
  std::set<Key> constant;
  for (int k = 0; k < kNumKeyframes; ++k) constant.insert(X(k));
  const SolveReport report = solve(window.graph, values, tightOptions(GetParam()), constant);
  std::printf("every pose constant, %s: %s\n", toString(GetParam()), report.linear_solver.c_str());
  EXPECT_TRUE(report.converged) << report.toString();
  EXPECT_EQ(report.num_free_parameters, 3 * static_cast<int>(window.landmarks.size()));
  expectPosesUnchanged(values, start, 0, kNumKeyframes);
  EXPECT_LT(maxLandmarkError(window, values, window.landmarks), 1e-6) << report.toString();
}

// Every landmark constant (motion-only BA, e.g. tracking against the map):
// nothing to eliminate, the poses are solved directly.
TEST_P(SlidingWindowTest, EveryLandmarkConstantSolvesThePosesAlone) {
  const Window window = makeWindow();
  Values values = window.values;
  std::set<Key> constant = window.constant;
  for (const int i : window.landmarks) {
    values.updatePoint(L(i), window.transect.p_W[i]);
    constant.insert(L(i));
  }
  const SolveReport report = solve(window.graph, values, tightOptions(GetParam()), constant);
  std::printf("every landmark constant, %s: %s\n", toString(GetParam()),
              report.linear_solver.c_str());
  EXPECT_TRUE(report.converged) << report.toString();
  EXPECT_EQ(report.num_eliminated_landmarks, 0u);
  EXPECT_EQ(report.num_free_parameters, 6 * (kWindowEnd - kFirstFree));
  EXPECT_LT(maxPoseError(window, values, kFirstFree, kWindowEnd), 1e-7) << report.toString();
  EXPECT_LT(maxLandmarkError(window, values, window.landmarks), 1e-15);
}

// A landmark seen by a single constant keyframe has no depth: its Jacobian
// block is rank 2. The solve stays usable, the rest of the window is
// unaffected, and the landmark only slides along its ray (it still projects
// onto its pixel).
TEST_P(SlidingWindowTest, ALandmarkSeenOnceByAConstantKeyframeLeavesTheSolveUsable) {
  Window window = makeWindow();
  const Key lonely = L(100000);
  const SE3d& T_W_C0 = window.transect.T_W_C[0];
  const Eigen::Vector3d p_W = T_W_C0 * Eigen::Vector3d(0.2, -0.1, 3.0);
  const PinholeRadtanCamera camera(window.transect.camera);
  const Eigen::Vector2d pixel = camera.project(Eigen::Vector3d(T_W_C0.inverse() * p_W));
  window.graph.emplace<ReprojectionFactor>(X(0), lonely, pixel, window.transect.camera,
                                           NoiseModel::isotropic(2, 0.5));
  window.values.insertPoint(lonely, p_W + Eigen::Vector3d(0.1, 0.05, -0.2));
  Values values = window.values;

  const SolveReport report = solve(window.graph, values, tightOptions(GetParam()), window.constant);
  EXPECT_TRUE(report.usable) << report.toString();
  EXPECT_LT(maxPoseError(window, values, kFirstFree, kWindowEnd), 1e-7) << report.toString();
  EXPECT_LT(maxLandmarkError(window, values, window.landmarks), 1e-6);
  const Eigen::Vector3d p_C = T_W_C0.inverse() * values.point(lonely);
  EXPECT_GT(p_C.z(), 0.0);
  EXPECT_LT((camera.project(p_C) - pixel).norm(), 1e-6);
}

}  // namespace
}  // namespace hsmap
