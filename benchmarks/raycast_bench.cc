// Ray casting throughput of MeshRayCaster on a seabed the size the simulator
// renders: a 1300 x 300 vertex height field (2 cm cells, 776,802 triangles,
// 26 m x 6 m) about 40 m deep, seen by a down-looking 960 x 540 pinhole camera
// 2 m above it (one ray per pixel, 518,400 rays per frame).
//
//   BM_SceneBuild             constructing the caster (BVH build, HIGH quality)
//   BM_CameraFrameSingleRays  a frame as a loop of intersect(ray)
//   BM_CameraFrameBatch       a frame as intersect(rays, hits), one row per batch
//   BM_ScatteredRays*         random origins and directions (incoherent rays),
//                             where the batch's packets gain nothing
// The argument is the number of TBB threads (tbb::global_control); rows are
// spread over them with tbb::parallel_for. Rates are items_per_second (rays).

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "core/raycast/mesh_ray_caster.h"

namespace {

using namespace hsmap;

constexpr int kGridX = 1300, kGridY = 300;  // vertices north x east
constexpr double kCell = 0.02;              // metres
constexpr int kWidth = 960, kHeight = 540;  // camera pixels
constexpr double kFocal = 800.0;            // pixels

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;
};

// Seabed depth (NED, z down): 40 m with metre-scale undulation and
// decimetre-scale ripples.
double seabedDepth(double x, double y) {
  return 40.0 + 0.3 * std::sin(x) * std::cos(y) + 0.02 * std::sin(7.0 * x + 3.0 * y);
}

const Mesh& seabed() {
  static const Mesh mesh = [] {
    Mesh m;
    m.vertices.reserve(kGridX * kGridY);
    for (int i = 0; i < kGridX; ++i) {
      for (int j = 0; j < kGridY; ++j) {
        const double x = i * kCell, y = j * kCell;
        m.vertices.emplace_back(x, y, seabedDepth(x, y));
      }
    }
    for (int i = 0; i + 1 < kGridX; ++i) {
      for (int j = 0; j + 1 < kGridY; ++j) {
        const int a = i * kGridY + j, b = a + kGridY, c = b + 1, d = a + 1;
        m.triangles.emplace_back(a, b, c);
        m.triangles.emplace_back(a, c, d);
      }
    }
    return m;
  }();
  return mesh;
}

const MeshRayCaster& caster() {
  static const MeshRayCaster instance(seabed().vertices, seabed().triangles);
  return instance;
}

// Camera over the middle of the field, 2 m above the mean seabed, looking
// down: image x (right) is east, image y (down) is south, the optical axis is
// +z (down). Rays in row-major pixel order.
std::vector<Ray> cameraRays() {
  Eigen::Matrix3d R_W_C;
  R_W_C.col(0) = Eigen::Vector3d::UnitY();
  R_W_C.col(1) = -Eigen::Vector3d::UnitX();
  R_W_C.col(2) = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d p_W_C(0.5 * (kGridX - 1) * kCell, 0.5 * (kGridY - 1) * kCell, 38.0);
  std::vector<Ray> rays(static_cast<std::size_t>(kWidth) * kHeight);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) {
      const Eigen::Vector3d d_C((col + 0.5 - 0.5 * kWidth) / kFocal,
                                (row + 0.5 - 0.5 * kHeight) / kFocal, 1.0);
      Ray& ray = rays[static_cast<std::size_t>(row) * kWidth + col];
      ray.origin = p_W_C;
      ray.direction = (R_W_C * d_C).normalized();
    }
  }
  return rays;
}

// Random origins 1-3 m above the field and random directions within 60
// degrees of nadir: the same hit rate as the camera, no coherence.
std::vector<Ray> scatteredRays() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> x(0.0, (kGridX - 1) * kCell), y(0.0, (kGridY - 1) * kCell);
  std::uniform_real_distribution<double> z(37.0, 39.0), tilt(-1.0, 1.0);
  std::vector<Ray> rays(static_cast<std::size_t>(kWidth) * kHeight);
  for (Ray& ray : rays) {
    ray.origin = Eigen::Vector3d(x(rng), y(rng), z(rng));
    ray.direction = Eigen::Vector3d(tilt(rng), tilt(rng), 1.0).normalized();
  }
  return rays;
}

const std::vector<Ray>& frame() {
  static const std::vector<Ray> rays = cameraRays();
  return rays;
}

const std::vector<Ray>& scattered() {
  static const std::vector<Ray> rays = scatteredRays();
  return rays;
}

void BM_SceneBuild(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  const Mesh& mesh = seabed();
  for (auto _ : state) {
    MeshRayCaster built(mesh.vertices, mesh.triangles);
    benchmark::DoNotOptimize(built.triangleCount());
  }
  state.counters["triangles"] = static_cast<double>(mesh.triangles.size());
}
BENCHMARK(BM_SceneBuild)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Casts `rays` (rows of kWidth) with tbb::parallel_for over rows, either ray by
// ray or one batch per row.
void castRows(const std::vector<Ray>& rays, std::vector<RayHit>& hits, bool batch) {
  const MeshRayCaster& mesh = caster();
  tbb::parallel_for(tbb::blocked_range<int>(0, kHeight), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row < r.end(); ++row) {
      const std::size_t first = static_cast<std::size_t>(row) * kWidth;
      if (batch) {
        mesh.intersect(std::span<const Ray>(rays.data() + first, kWidth),
                       std::span<RayHit>(hits.data() + first, kWidth));
      } else {
        for (std::size_t i = first; i < first + kWidth; ++i) hits[i] = mesh.intersect(rays[i]);
      }
    }
  });
}

void runFrames(benchmark::State& state, const std::vector<Ray>& rays, bool batch) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  caster();  // built outside the timed loop
  std::vector<RayHit> hits(rays.size());
  for (auto _ : state) {
    castRows(rays, hits, batch);
    benchmark::ClobberMemory();
  }
  std::size_t hit_count = 0;
  for (const RayHit& hit : hits) hit_count += hit.hit();
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(rays.size()));
  state.counters["hit_fraction"] = static_cast<double>(hit_count) / rays.size();
}

void BM_CameraFrameSingleRays(benchmark::State& state) { runFrames(state, frame(), false); }
void BM_CameraFrameBatch(benchmark::State& state) { runFrames(state, frame(), true); }
void BM_ScatteredRaysSingle(benchmark::State& state) { runFrames(state, scattered(), false); }
void BM_ScatteredRaysBatch(benchmark::State& state) { runFrames(state, scattered(), true); }
BENCHMARK(BM_CameraFrameSingleRays)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CameraFrameBatch)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ScatteredRaysSingle)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ScatteredRaysBatch)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
