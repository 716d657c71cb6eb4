// Benchmarks of the simulator's scene: building the seabed mesh of each
// terrain preset at the default extent (26 m x 6 m at 2 cm, the rugged one
// with its rocks), the bare height field, and the material field's
// abundances() (seabed and rock surfaces), which the renderers call for every
// ray hit (a 960x540 frame with 2x2 samples is 2M calls).

#include <benchmark/benchmark.h>

#include "pipelines/simulate/scene/material_field.h"
#include "pipelines/simulate/scene/seabed_height_field.h"
#include "pipelines/simulate/scene/seabed_scene.h"

namespace {

using namespace hsmap;

void BM_BuildSeabedScene(benchmark::State& state) {
  SeabedSceneConfig config;
  config.terrain = static_cast<TerrainPreset>(state.range(0));
  std::size_t triangles = 0;
  for (auto _ : state) {
    const SeabedScene scene = buildSeabedScene(config);
    triangles = scene.triangles.size();
    benchmark::DoNotOptimize(scene.vertices.data());
  }
  state.SetLabel(terrainPresetName(config.terrain));
  state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_BuildSeabedScene)
    ->Arg(static_cast<int>(TerrainPreset::flat))
    ->Arg(static_cast<int>(TerrainPreset::low_relief))
    ->Arg(static_cast<int>(TerrainPreset::rugged))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_HeightFieldZ(benchmark::State& state) {
  SeabedSceneConfig config;
  config.terrain = static_cast<TerrainPreset>(state.range(0));
  const SeabedHeightField field(config);
  double north = 0.0, east = -0.7;
  for (auto _ : state) {
    benchmark::DoNotOptimize(field.z(north, east));
    north += 0.0013;  // walk along the track: scarp and ridge included
    if (north > 20.0) north = 0.0;
  }
  state.SetLabel(terrainPresetName(config.terrain));
}
BENCHMARK(BM_HeightFieldZ)
    ->Arg(static_cast<int>(TerrainPreset::flat))
    ->Arg(static_cast<int>(TerrainPreset::rugged));

void BM_Abundances(benchmark::State& state) {
  const MaterialField field(1);
  const auto kind = static_cast<SurfaceKind>(state.range(0));
  Eigen::Vector3d p_W(0.0, -0.7, 40.0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(field.abundances(p_W, kind));
    // Successive calls a pixel apart, as a renderer makes them.
    p_W.x() += 0.0025;
    p_W.y() += 0.0007;
    if (p_W.x() > 20.0) p_W.x() = 0.0;
    if (p_W.y() > 1.0) p_W.y() = -1.0;
  }
  state.SetLabel(kind == SurfaceKind::rock ? "rock" : "seabed");
}
BENCHMARK(BM_Abundances)
    ->Arg(static_cast<int>(SurfaceKind::seabed))
    ->Arg(static_cast<int>(SurfaceKind::rock));

}  // namespace

BENCHMARK_MAIN();
