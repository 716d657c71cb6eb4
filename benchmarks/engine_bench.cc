// The factor-graph engine on survey-sized synthetic problems (the transect of
// tests/support/synthetic_transect.h, scaled up), solved from a noisy start
// with the default SolverOptions (Levenberg-Marquardt, SPARSE_SCHUR with
// SuiteSparse, every hardware thread):
//
//   BM_KeyframeBundleAdjustment: 1,000 keyframes, 50,000 landmarks, ~500,000
//     ReprojectionFactors (0.5 px noise, Huber), INS position + attitude on
//     every keyframe. Start: poses 0.2 m / 2 deg, landmarks 0.2 m off.
//   BM_SplineJointCalibration: the same scene and pixels, but the camera pose
//     of every frame is the 0.1 s-knot SE(3) B-spline at the frame time
//     (SplineReprojectionFactor), plus 50,000 PushbroomLineFactors (known
//     points) that estimate T_C_U and d with the trajectory; the control
//     points carry INS-derived pose priors (factors/ has no spline INS
//     factor), T_C_U and d their survey priors. Start: control points
//     0.2 m / 2 deg, landmarks 0.2 m, T_C_U 2 deg / 5 cm, d 15 ms off.
//
// Only the solve is timed (problem construction is reported separately as a
// counter). Counters: solve_s, setup_s, iterations, initial_cost, final_cost,
// residuals, and the errors after the solve. Figures and the command are in
// docs/BENCHMARKS.md, section "Engine".

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <random>

#include "factors/extrinsic_prior_factor.h"
#include "factors/pose_prior_factor.h"
#include "factors/pushbroom_line_factor.h"
#include "factors/spline_reprojection_factor.h"
#include "factors/spline_timing.h"
#include "factors/time_offset_prior_factor.h"
#include "solvers/graph_solver.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// 1,000 keyframes 0.25 m apart (0.5 s at 0.5 m/s), so a seabed point stays
// in the 2.88 m along-track footprint for ~10 keyframes: 50,000 landmarks give
// ~500,000 observations.
test::TransectConfig surveyConfig() {
  test::TransectConfig config;
  config.seed = 2024;
  config.num_keyframes = 1000;
  config.keyframe_interval_s = 0.5;
  config.num_landmarks = 50000;
  return config;
}

const test::Transect& survey() {
  static const test::Transect transect = test::makeTransect(surveyConfig());
  return transect;
}

// The benchmark's argument picks the linear solver preset.
SolverOptions optionsFor(const benchmark::State& state) {
  SolverOptions options;
  options.linear_solver = static_cast<SolverOptions::LinearSolver>(state.range(0));
  return options;
}

void reportSolve(benchmark::State& state, const SolveReport& report, double setup_s) {
  state.counters["solve_s"] = report.wall_time_s;
  state.counters["setup_s"] = setup_s;
  state.counters["jacobian_eval_s"] = report.jacobian_evaluation_s;
  state.counters["linear_solver_s"] = report.linear_solver_s;
  state.counters["iterations"] = report.iterations;
  state.counters["initial_cost"] = report.initial_cost;
  state.counters["final_cost"] = report.final_cost;
  state.counters["residuals"] = report.num_residuals;
  state.counters["converged"] = report.converged ? 1 : 0;
  state.SetLabel(report.linear_solver + ", " + report.termination + ": " + report.reason);
}

void BM_KeyframeBundleAdjustment(benchmark::State& state) {
  const test::Transect& transect = survey();
  for (auto _ : state) {
    state.PauseTiming();
    const auto setup_start = std::chrono::steady_clock::now();
    FactorGraph graph;
    Values values;
    test::buildBundleAdjustment(transect, RobustLoss::huber(2.0), &graph, &values);
    GraphProblem problem(graph, values);
    const double setup_s = secondsSince(setup_start);
    state.ResumeTiming();

    const SolveReport report = solve(problem, optionsFor(state));

    state.PauseTiming();
    reportSolve(state, report, setup_s);
    double position = 0.0;
    for (std::size_t k = 0; k < transect.T_W_C.size(); ++k) {
      position += (values.poseTranslation(X(k)) - transect.T_W_C[k].t).squaredNorm();
    }
    double landmark = 0.0;
    for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
      landmark += (values.point(L(i)) - transect.p_W[i]).squaredNorm();
    }
    state.counters["keyframes"] = transect.T_W_C.size();
    state.counters["landmarks"] = transect.p_W.size();
    state.counters["observations"] = transect.observations.size();
    state.counters["position_rmse_m"] = std::sqrt(position / transect.T_W_C.size());
    state.counters["landmark_rmse_m"] = std::sqrt(landmark / transect.p_W.size());
    state.ResumeTiming();
  }
}
BENCHMARK(BM_KeyframeBundleAdjustment)
    ->ArgName("linear_solver")
    ->Arg(static_cast<int>(SolverOptions::LinearSolver::sparse_schur))
    ->Arg(static_cast<int>(SolverOptions::LinearSolver::iterative_schur))
    ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_SplineJointCalibration(benchmark::State& state) {
  const test::Transect& transect = survey();
  const test::TransectConfig& config = transect.config;
  const SE3Splined& spline = transect.truth_spline;
  const SplineTiming timing = SplineTiming::of(spline);
  const PushbroomParameters uhi = test::uhiCamera();
  const SE3d T_C_U_true = test::uhiOnCamera();
  constexpr double kTrueOffset = 0.015;

  // 50,000 push-broom observations: 12,500 lines x 4 known points.
  std::mt19937 rng(7);
  std::vector<double> line_times;
  const double line_begin = 0.5;
  const double line_end = spline.validEnd() - 0.5;
  for (int k = 0; k < 12500; ++k) line_times.push_back(line_begin + (line_end - line_begin) * k / 12499.0);
  const auto pushbroom = test::makePushbroomObservations(spline, T_C_U_true, kTrueOffset, uhi,
                                                          line_times, 4, 0.3, config.altitude_m, rng);

  for (auto _ : state) {
    state.PauseTiming();
    const auto setup_start = std::chrono::steady_clock::now();
    FactorGraph graph;
    Values values;
    const NoiseModel pixel_noise = NoiseModel::isotropic(2, config.pixel_sigma);
    for (const test::PixelObservation& observation : transect.observations) {
      graph.emplace<SplineReprojectionFactor>(timing, transect.keyframe_times[observation.keyframe],
                                              L(observation.landmark), observation.pixel,
                                              transect.camera, pixel_noise, RobustLoss::huber(2.0));
    }
    // INS-derived priors on the control points (the INS pose at each knot,
    // with its noise), standing in for INS factors on the spline.
    const Vector6d control_point_sigmas =
        (Vector6d() << config.ins_sigma_horizontal_m, config.ins_sigma_horizontal_m,
         config.ins_sigma_depth_m, config.ins_sigma_roll_pitch_deg * kDeg,
         config.ins_sigma_roll_pitch_deg * kDeg, config.ins_sigma_heading_deg * kDeg)
            .finished();
    const NoiseModel control_point_noise = NoiseModel::fromSigmas(control_point_sigmas);
    std::mt19937 start_rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int j = 0; j < timing.num_control_points; ++j) {
      const SE3d& truth = spline.controlPoints()[j];
      Vector6d noise;
      for (int i = 0; i < 6; ++i) noise[i] = control_point_sigmas[i] * normal(start_rng);
      const SE3d measured = truth * SE3d::exp(noise);
      graph.emplace<PosePriorFactor>(S(j), measured, control_point_noise);
      const SE3d start = truth * SE3d::exp(test::gaussian6(start_rng, 0.2, 2.0 * kDeg));
      values.insertPose(S(j), start.q, start.t);
    }
    for (std::size_t i = 0; i < transect.p_W.size(); ++i) {
      values.insertPoint(L(i), transect.start_p_W[i]);
    }
    // T_C_U and d: survey priors (CAD guess 2 deg / 5 cm off, d guessed 0)
    // and the start at those guesses.
    const SE3d T_C_U_guess(T_C_U_true.q * expSO3(Eigen::Vector3d(2.0 * kDeg, 0.0, 0.0)),
                           T_C_U_true.t + Eigen::Vector3d(0.0, 0.05, 0.0));
    const double d_guess = 0.0;
    graph.emplace<ExtrinsicPriorFactor>(E(0), T_C_U_guess,
                                        ExtrinsicPriorFactor::noiseFromSigmas(5.0, 0.2));
    graph.emplace<TimeOffsetPriorFactor>(D(0), d_guess, NoiseModel::isotropic(1, 0.05));
    values.insertPose(E(0), T_C_U_guess.q, T_C_U_guess.t);
    values.insertScalar(D(0), d_guess);
    const NoiseModel line_noise =
        NoiseModel::fromSigmas(Eigen::Vector2d(0.3, test::acrossLineSigma(uhi)));
    for (const auto& observation : pushbroom) {
      graph.emplace<PushbroomLineFactor>(timing, d_guess, E(0), D(0), observation.p_W,
                                         observation.observation, uhi, line_noise,
                                         RobustLoss::huber(2.0));
    }
    GraphProblem problem(graph, values);
    const double setup_s = secondsSince(setup_start);
    state.ResumeTiming();

    const SolveReport report = solve(problem, optionsFor(state));

    state.PauseTiming();
    reportSolve(state, report, setup_s);
    const SE3d T_C_U(values.poseRotation(E(0)), values.poseTranslation(E(0)));
    state.counters["control_points"] = timing.num_control_points;
    state.counters["reprojections"] = transect.observations.size();
    state.counters["pushbroom_observations"] = pushbroom.size();
    state.counters["T_C_U_rotation_error_deg"] =
        logSO3(T_C_U_true.q.conjugate() * T_C_U.q).norm() / kDeg;
    state.counters["T_C_U_translation_error_m"] = (T_C_U.t - T_C_U_true.t).norm();
    state.counters["d_error_ms"] = 1e3 * std::abs(values.scalar(D(0)) - kTrueOffset);
    std::vector<SE3d> estimated;
    for (int j = 0; j < timing.num_control_points; ++j) {
      estimated.emplace_back(values.poseRotation(S(j)), values.poseTranslation(S(j)));
    }
    const SE3Splined fitted(timing.t0, timing.dt, estimated);
    double position = 0.0;
    for (std::size_t k = 0; k < transect.keyframe_times.size(); ++k) {
      position += (fitted.pose(transect.keyframe_times[k]).t - transect.T_W_C[k].t).squaredNorm();
    }
    state.counters["frame_position_rmse_m"] = std::sqrt(position / transect.keyframe_times.size());
    state.ResumeTiming();
  }
}
BENCHMARK(BM_SplineJointCalibration)
    ->ArgName("linear_solver")
    ->Arg(static_cast<int>(SolverOptions::LinearSolver::sparse_schur))
    ->Arg(static_cast<int>(SolverOptions::LinearSolver::iterative_schur))
    ->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace hsmap

BENCHMARK_MAIN();
