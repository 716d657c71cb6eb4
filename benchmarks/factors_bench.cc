// Micro benchmarks of one factor evaluation as the solver performs it:
// ceres::CostFunction::Evaluate with residual and all Jacobians, per factor
// type, at a realistic state. The time per evaluation times the number of
// factors of each kind bounds the Jacobian part of a solver iteration;
// "residual only" variants show the price of the derivatives. The spline
// factors have analytic Jacobians; their "autodiff" variants time the
// autodiff reference (createAutoDiffCostFunction()) they replace.

#include <benchmark/benchmark.h>
#include <ceres/cost_function.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/se3_bspline.h"
#include "factors/between_pose_factor.h"
#include "factors/extrinsic_prior_factor.h"
#include "factors/ins_attitude_factor.h"
#include "factors/ins_position_factor.h"
#include "factors/pose_prior_factor.h"
#include "factors/pushbroom_line_factor.h"
#include "factors/reprojection_factor.h"
#include "factors/reprojection_with_intrinsics_factor.h"
#include "factors/spline_reprojection_factor.h"
#include "factors/spline_smoothness_factor.h"
#include "factors/time_offset_prior_factor.h"

namespace {

using namespace hsmap;

constexpr double kT0 = 10.0;
constexpr double kDt = 0.1;

PinholeRadtanParameters rgbCamera() {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = p.fy = 800.0;
  p.cx = 480.0;
  p.cy = 270.0;
  p.distortion = {-0.28, 0.09, 0.001, -0.001, -0.01};
  return p;
}

PushbroomParameters uhiCamera() {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = 1500.0;
  p.cx = 960.0;
  p.distortion = {0.05, -0.01};
  return p;
}

SE3Splined trajectory() {
  std::vector<SE3d> control_points;
  for (int k = 0; k < 20; ++k) {
    const double t = kT0 + (k - 1) * kDt;
    control_points.emplace_back(
        expSO3(Eigen::Vector3d(0.1 * std::sin(2.0 * t), 0.05 * std::cos(t), 0.3 * t)),
        Eigen::Vector3d(0.8 * t, 0.2 * std::sin(t), 5.0));
  }
  return SE3Splined(kT0, kDt, control_points);
}

// Owns the parameter blocks of one state and evaluates a cost function on them.
class Evaluation {
 public:
  Evaluation(std::unique_ptr<ceres::CostFunction> cost, std::vector<std::vector<double>> blocks)
      : cost_(std::move(cost)), blocks_(std::move(blocks)) {
    for (const auto& block : blocks_) parameters_.push_back(block.data());
    residual_.resize(cost_->num_residuals());
    for (const auto& block : blocks_) {
      jacobian_storage_.emplace_back(block.size() * residual_.size());
    }
    for (auto& storage : jacobian_storage_) jacobians_.push_back(storage.data());
  }

  bool run(bool with_jacobians) {
    return cost_->Evaluate(parameters_.data(), residual_.data(),
                           with_jacobians ? jacobians_.data() : nullptr);
  }
  const std::vector<double>& residual() const { return residual_; }

 private:
  std::unique_ptr<ceres::CostFunction> cost_;
  std::vector<std::vector<double>> blocks_;
  std::vector<const double*> parameters_;
  std::vector<double> residual_;
  std::vector<std::vector<double>> jacobian_storage_;
  std::vector<double*> jacobians_;
};

std::vector<double> pose(const SE3d& T) {
  std::vector<double> block(SE3d::kNumParameters);
  T.toParameters(block.data());
  return block;
}

std::vector<double> point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

// range(0) = 1: residual and Jacobians (what the solver asks for at every
// linearisation); 0: residual only (line search, cost checks).
void runBenchmark(benchmark::State& state, Evaluation evaluation,
                  const std::string& label_suffix = "") {
  const bool with_jacobians = state.range(0) != 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluation.run(with_jacobians));
    benchmark::DoNotOptimize(evaluation.residual().data());
  }
  state.SetLabel(std::string(with_jacobians ? "residual+jacobians" : "residual only") +
                 label_suffix);
}

const SE3d kPose(expSO3(Eigen::Vector3d(0.3, -0.2, 1.1)), Eigen::Vector3d(4.0, -2.0, 6.0));
const Eigen::Vector3d kLandmark = kPose * Eigen::Vector3d(0.3, -0.2, 3.0);

void BM_ReprojectionFactor(benchmark::State& state) {
  const ReprojectionFactor factor(X(0), L(0), Eigen::Vector2d(500.0, 200.0), rgbCamera(),
                                  NoiseModel::isotropic(2, 1.0));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {pose(kPose), point(kLandmark)}));
}

void BM_ReprojectionWithIntrinsicsFactor(benchmark::State& state) {
  const ReprojectionWithIntrinsicsFactor factor(X(0), L(0), K(0), Eigen::Vector2d(500.0, 200.0),
                                                NoiseModel::isotropic(2, 1.0));
  const std::array<double, PinholeRadtanCamera::kNumIntrinsics> k =
      PinholeRadtanCamera(rgbCamera()).intrinsics();
  runBenchmark(state, Evaluation(factor.createCostFunction(),
                                 {pose(kPose), point(kLandmark),
                                  std::vector<double>(k.begin(), k.end())}));
}

void BM_InsPositionFactor(benchmark::State& state) {
  const InsPositionFactor factor(X(0), Eigen::Vector3d(4.0, -2.0, 6.0),
                                 SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.5, 0, 0.3)),
                                 NoiseModel::fromSigmas(Eigen::Vector3d(0.5, 0.5, 0.05)));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {pose(kPose)}));
}

void BM_InsAttitudeFactor(benchmark::State& state) {
  const InsAttitudeFactor factor(X(0), expSO3(Eigen::Vector3d(0.3, -0.2, 1.0)), SE3d(),
                                 NoiseModel::isotropic(3, 0.001));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {pose(kPose)}));
}

void BM_PosePriorFactor(benchmark::State& state) {
  const PosePriorFactor factor(X(0), SE3d(), NoiseModel::isotropic(6, 0.1));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {pose(kPose)}));
}

void BM_BetweenPoseFactor(benchmark::State& state) {
  const BetweenPoseFactor factor(X(0), X(1), SE3d(), NoiseModel::isotropic(6, 0.1));
  runBenchmark(state, Evaluation(factor.createCostFunction(),
                                 {pose(kPose), pose(kPose * SE3d::exp(Vector6d::Constant(0.1)))}));
}

void BM_ExtrinsicPriorFactor(benchmark::State& state) {
  const ExtrinsicPriorFactor factor(E(0), SE3d(), ExtrinsicPriorFactor::noiseFromSigmas(2.0, 0.05));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {pose(kPose)}));
}

void BM_TimeOffsetPriorFactor(benchmark::State& state) {
  const TimeOffsetPriorFactor factor(D(0), 0.0, NoiseModel::isotropic(1, 0.05));
  runBenchmark(state, Evaluation(factor.createCostFunction(), {{0.01}}));
}

// The spline factors' last argument (range(autodiff_arg)): 0 = analytic
// Jacobians (what the solver uses), 1 = the autodiff reference.
std::unique_ptr<ceres::CostFunction> splineCost(const benchmark::State& state, int autodiff_arg,
                                                const auto& factor) {
  return state.range(autodiff_arg) != 0 ? factor.createAutoDiffCostFunction()
                                        : factor.createCostFunction();
}

const char* splineLabel(const benchmark::State& state, int autodiff_arg) {
  return state.range(autodiff_arg) != 0 ? ", autodiff" : ", analytic";
}

void BM_SplineReprojectionFactor(benchmark::State& state) {
  const SE3Splined spline = trajectory();
  const double t = kT0 + 5.3 * kDt;
  const SplineReprojectionFactor factor(SplineTiming::of(spline), t, L(0),
                                        Eigen::Vector2d(500.0, 200.0), rgbCamera(),
                                        NoiseModel::isotropic(2, 1.0));
  std::vector<std::vector<double>> blocks;
  for (int k = 0; k < 4; ++k) {
    blocks.push_back(pose(spline.controlPoints()[factor.segment().first_control_point + k]));
  }
  blocks.push_back(point(spline.pose(t) * Eigen::Vector3d(0.3, -0.2, 3.0)));
  runBenchmark(state, Evaluation(splineCost(state, 1, factor), blocks), splineLabel(state, 1));
}

void BM_PushbroomLineFactor(benchmark::State& state) {
  const SE3Splined spline = trajectory();
  const double t_recorded = kT0 + 7.4 * kDt;
  const SE3d T_C_U(expSO3(Eigen::Vector3d(0.0, 0.0, 1.57)), Eigen::Vector3d(0.1, 0.0, 0.0));
  const Eigen::Vector3d p_W = spline.pose(t_recorded) * T_C_U * Eigen::Vector3d(0.4, 0.0, 3.0);
  const bool with_landmark = state.range(1) != 0;
  const PushbroomObservation observation{t_recorded, 1100.0};
  const NoiseModel noise = NoiseModel::fromSigmas(Eigen::Vector2d(0.5, 0.5 / 1500.0));
  const PushbroomLineFactor factor =
      with_landmark ? PushbroomLineFactor(SplineTiming::of(spline), 0.0, E(0), D(0), L(0),
                                          observation, uhiCamera(), noise)
                    : PushbroomLineFactor(SplineTiming::of(spline), 0.0, E(0), D(0), p_W,
                                          observation, uhiCamera(), noise);
  std::vector<std::vector<double>> blocks;
  for (int k = 0; k < PushbroomLineFactor::kNumControlPoints; ++k) {
    blocks.push_back(pose(spline.controlPoints()[factor.firstControlPoint() + k]));
  }
  blocks.push_back(pose(T_C_U));
  blocks.push_back({0.0});
  if (with_landmark) blocks.push_back(point(p_W));
  runBenchmark(state, Evaluation(splineCost(state, 2, factor), blocks),
               std::string(with_landmark ? ", landmark" : ", fixed point") +
                   splineLabel(state, 2));
}

void BM_SplineSmoothnessFactor(benchmark::State& state) {
  const SplineSmoothnessFactor factor(1, NoiseModel::isotropic(6, 0.01));
  const SE3d step = SE3d::exp(Vector6d::Constant(0.05));
  runBenchmark(state, Evaluation(factor.createCostFunction(),
                                 {pose(kPose), pose(kPose * step), pose(kPose * step * step)}));
}

}  // namespace

BENCHMARK(BM_ReprojectionFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_ReprojectionWithIntrinsicsFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_InsPositionFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_InsAttitudeFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_PosePriorFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_BetweenPoseFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_ExtrinsicPriorFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_TimeOffsetPriorFactor)->Arg(0)->Arg(1);
BENCHMARK(BM_SplineReprojectionFactor)->ArgsProduct({{0, 1}, {0, 1}});
BENCHMARK(BM_PushbroomLineFactor)->ArgsProduct({{0, 1}, {0, 1}, {0, 1}});
BENCHMARK(BM_SplineSmoothnessFactor)->Arg(0)->Arg(1);

BENCHMARK_MAIN();
