#pragma once
// MaterialField: what the seabed is made of at each surface point, as
// abundances of the spectral library's endmembers, and the reflectance that
// follows from them (linear mixing).
//
// The field is procedural: seeded 3D gradient noise (procedural_noise.h)
// thresholded into patches at three scales, painted over each other (each
// layer replaces a fraction alpha of the mixture below it by one endmember:
// a <- (1 - alpha) a + alpha e_k, which keeps a >= 0 and sum(a) = 1):
//   seabed  metres       sand / fine-sediment areas, soft edges over ~0.5 m;
//           decimetres   algae patches (more of them on sediment) and rarer
//                        coral/sponge-like patches, with edges a few mm wide;
//           centimetres  pebbles (rock) and shell grit (sand), blobs 0.5-1.5 cm
//                        across, each covering about 7% of the ground, with
//                        the strong brightness contrast that optical flow needs
//                        (at least 300 well-spread Shi-Tomasi corners per
//                        960x540 image at 1.25-3.75 mm per pixel, tested);
//   rock    rock-dominated (about 0.7 on average) with light and dark mineral
//           grains (cm), algae and sponge patches (dm) and a dusting of
//           sediment (m).
// Positions are 3D (p_W), so steep faces, boulder sides and overhangs are
// textured like the ground, without stretching; only the metre-scale
// sand/sediment areas of the seabed are drawn in plan view (north, east),
// where a slope's stretch of a metre-scale patch does not show.
//
// Contract: abundances() is a pure function of (seed, p_W, kind): the same
// inputs give bit-identical outputs in any thread and any call order. Each
// entry is >= 0 and they sum to 1 (within float rounding, < 1e-6). Cost: about
// 0.1-0.12 us of CPU per call (benchmarks/simulate_scene_bench.cc), no allocation.
//
// Reflectance: with E = endmemberMatrix(wavelengths) (rows = wavelengths,
// cols = endmembers in Endmember order), the reflectance at those
// wavelengths is E * a.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "pipelines/simulate/scene/seabed_scene.h"
#include "pipelines/simulate/scene/spectral_library.h"

namespace hsmap {

using Abundances = std::array<float, kEndmemberCount>;  // >= 0, sum to 1, Endmember order

class MaterialField {
 public:
  explicit MaterialField(std::uint64_t seed);

  // Mixture at a surface point (3D, so that boulder sides and overhangs are textured too).
  Abundances abundances(const Eigen::Vector3d& p_W, SurfaceKind kind) const;

  // Reflectance of the mixture at the given wavelengths: rows = wavelengths, cols = endmembers,
  // so reflectance = endmemberMatrix(w) * abundances. Throws std::invalid_argument for a
  // wavelength outside the spectral library's [350, 1000] nm.
  static Eigen::MatrixXf endmemberMatrix(const std::vector<double>& wavelengths_nm);

 private:
  Abundances seabed(const Eigen::Vector3d& p_W) const;
  Abundances rock(const Eigen::Vector3d& p_W) const;

  // Independent noise seeds of the layers, drawn from the constructor's seed.
  std::uint64_t areas_seed_, algae_seed_, coral_seed_, grit_seed_;
  std::uint64_t rock_grain_seed_, rock_algae_seed_, rock_sponge_seed_, rock_dust_seed_;
};

}  // namespace hsmap
