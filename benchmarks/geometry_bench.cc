// Micro benchmarks of the geometry kernels that sit inside every factor
// evaluation: camera projection / unprojection and SE(3) spline evaluation,
// in double and with the Jets a Ceres autodiff cost function uses (4 spline
// control points of 7 parameters = 28 derivatives).

#include <benchmark/benchmark.h>
#include <ceres/jet.h>

#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/se3_bspline.h"

namespace {

using namespace hsmap;

PinholeRadtanCamera pinhole() {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = p.fy = 800.0;
  p.cx = 480.0;
  p.cy = 270.0;
  p.distortion = {-0.28, 0.09, 0.001, -0.001, -0.01};
  return PinholeRadtanCamera(p);
}

PushbroomCamera pushbroom() {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = 1500.0;
  p.cx = 960.0;
  p.distortion = {0.05, -0.01};
  return PushbroomCamera(p);
}

SE3Splined spline() {
  std::vector<SE3d> control_points;
  for (int k = 0; k < 8; ++k) {
    Vector6d xi;
    xi << 0.5 * k, 0.1 * k, 0.02 * k * k, 0.01 * k, -0.02 * k, 0.1 * k;
    control_points.push_back(SE3d::exp(xi));
  }
  return SE3Splined(0.0, 0.1, control_points);
}

void BM_PinholeProject(benchmark::State& state) {
  const PinholeRadtanCamera camera = pinhole();
  Eigen::Vector3d p(0.4, -0.2, 3.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera.project(p));
    p.x() += 1e-9;
  }
}
BENCHMARK(BM_PinholeProject);

void BM_PinholeUnproject(benchmark::State& state) {
  const PinholeRadtanCamera camera = pinhole();
  Eigen::Vector2d pixel(812.0, 77.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera.unproject(pixel));
    pixel.x() += 1e-9;
  }
}
BENCHMARK(BM_PinholeUnproject);

void BM_PushbroomProject(benchmark::State& state) {
  const PushbroomCamera camera = pushbroom();
  Eigen::Vector3d p(0.4, 0.001, 3.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(camera.project(p));
    p.x() += 1e-9;
  }
}
BENCHMARK(BM_PushbroomProject);

void BM_SplinePose(benchmark::State& state) {
  const SE3Splined s = spline();
  double t = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.pose(t));
    t = t > 0.4 ? 0.1 : t + 1e-3;
  }
}
BENCHMARK(BM_SplinePose);

void BM_SplineKinematics(benchmark::State& state) {
  const SE3Splined s = spline();
  double t = 0.1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.kinematics(t));
    t = t > 0.4 ? 0.1 : t + 1e-3;
  }
}
BENCHMARK(BM_SplineKinematics);

void BM_SplinePoseJet28(benchmark::State& state) {
  using Jet = ceres::Jet<double, 28>;
  const SE3Splined s = spline();
  std::array<std::array<Jet, 7>, 4> blocks;
  for (int i = 0; i < 4; ++i) {
    double raw[7];
    s.controlPoints()[2 + i].toParameters(raw);
    for (int j = 0; j < 7; ++j) blocks[i][j] = Jet(raw[j], 7 * i + j);
  }
  const Jet* pointers[4] = {blocks[0].data(), blocks[1].data(), blocks[2].data(),
                            blocks[3].data()};
  double u = 0.3;
  for (auto _ : state) {
    benchmark::DoNotOptimize(evaluateSe3Spline<Jet>(pointers, Jet(u)));
    u = u > 0.9 ? 0.1 : u + 1e-3;
  }
}
BENCHMARK(BM_SplinePoseJet28);

}  // namespace

BENCHMARK_MAIN();
