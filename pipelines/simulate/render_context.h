#pragma once
// RenderContext: what the RGB and UHI renderers share: the scene, its ray
// caster, its material field and the vehicle's lamps.
#include <cstdint>

#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"
#include "pipelines/simulate/scene/material_field.h"
#include "pipelines/simulate/scene/seabed_scene.h"
#include "pipelines/simulate/rgb_marine_snow.h"
#include "pipelines/simulate/underwater_optics.h"
#include "pipelines/simulate/water_backscatter.h"

namespace hsmap {

struct RenderContext {
  const SeabedScene* scene = nullptr;
  const MeshRayCaster* caster = nullptr;
  const MaterialField* materials = nullptr;
  const LampRig* lamps = nullptr;
  double turbidity = 1.0;
  bool shadows = true;
  // Nominal altitude, for the fixed exposure of both cameras.
  double nominal_altitude_m = 2.0;
  // Light scattered by the water into the cameras (off by default), and the
  // cameras on the vehicle, which place the lamps relative to each camera.
  WaterBackscatterConfig backscatter;
  MarineSnowConfig marine_snow;  // particles in front of the RGB camera (off by default)
  SE3d T_B_C;
  SE3d T_C_U;

  const MeshRayCaster* shadowCaster() const { return shadows ? caster : nullptr; }
  SurfaceKind kindOf(int triangle) const { return scene->triangle_kind[triangle]; }
};

// A deterministic seed for the noise of one image row (or scan line), so that
// rows rendered in parallel, in any order, give the same bytes.
inline std::uint64_t noiseSeed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
                    (index + 1) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  x *= 0xD6E8FEB86659FD93ull;
  x ^= x >> 32;
  return x;
}

}  // namespace hsmap
