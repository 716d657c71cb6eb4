#pragma once
// The true-surface samples that mesh_completeness is measured on
// (DATASET.md: "fraction of true-surface samples within 2 cm of the mapped
// mesh, over the true ortho-image's footprint").
//
// The footprint is the set of valid pixels of truth/reflectance.hdr (ENVI,
// north-up, `map info = {Arbitrary, 1, 1, E, N, px, px, units=Meters}` in W):
// a pixel is valid when any of its bands is a number, since the simulator
// writes NaN in every band where the UHI never looked. A sample is the true
// surface under a valid pixel's centre: the first hit of a vertical ray cast
// downwards (+z in NED) from above the whole scene onto truth/scene.ply, i.e.
// the topmost surface, as the simulator defines the true ortho-image
// (pipelines/simulate/reflectance_ortho.h). A valid pixel whose ray misses the
// scene (not expected from the simulator) is counted, not sampled.
//
// Pixel centres: with the reference pixel (x_ref, y_ref) 1-based at the
// upper-left corner of the upper-left pixel (ENVI), the centre of row r,
// column c (0-based) is
//   east  = E + (c + 1.5 - x_ref) * px_x,   north = N - (r + 1.5 - y_ref) * px_y.
//
// Bounded cost: a 100 m transect at 1 cm pixels has millions of pixels, and
// a completeness fraction needs far fewer samples to be known to well under
// 1 %. Only every stride-th row and column are read (rows and columns 0, s,
// 2s, ...), with s the smallest stride for which that lattice has at most
// max_samples pixels (footprintStride); rows off the lattice are never read.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "core/raycast/mesh_ray_caster.h"

namespace hsmap {

// The default bound on the number of samples (docs/EVALUATE.md).
inline constexpr std::int64_t kDefaultMaxFootprintSamples = 200000;

struct TrueSurfaceSamples {
  std::vector<Eigen::Vector3d> points_W;  // true surface under sampled footprint pixel centres
  int stride = 1;                         // every stride-th row and column of the raster
  std::int64_t footprint_pixels = 0;      // valid pixels on the sampled lattice
  std::int64_t missed_pixels = 0;         // of those, pixels whose vertical ray missed the scene
};

// The smallest s >= 1 with ceil(rows / s) * ceil(cols / s) <= max_samples.
// std::invalid_argument unless rows, cols and max_samples are positive.
int footprintStride(int rows, int cols, std::int64_t max_samples);

// `scene` is truth/scene.ply in W. Throws InputError naming the header when
// it has no map info, a map info that is not in local W (`Arbitrary`) or
// pixel sizes that are not positive, and what EnviReader throws for a bad
// raster.
TrueSurfaceSamples sampleTrueSurface(const MeshRayCaster& scene,
                                     const std::filesystem::path& reflectance_hdr,
                                     std::int64_t max_samples = kDefaultMaxFootprintSamples);

}  // namespace hsmap
