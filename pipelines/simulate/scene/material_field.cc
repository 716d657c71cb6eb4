#include "pipelines/simulate/scene/material_field.h"

#include <random>

#include "pipelines/simulate/scene/procedural_noise.h"

namespace hsmap {

namespace {

constexpr int kSand = static_cast<int>(Endmember::sand);
constexpr int kSediment = static_cast<int>(Endmember::sediment);
constexpr int kRock = static_cast<int>(Endmember::rock);
constexpr int kCoral = static_cast<int>(Endmember::coral);
constexpr int kAlgae = static_cast<int>(Endmember::algae);

// A mixture under construction, in double so that painting many layers does
// not accumulate float rounding in the sum.
struct Mixture {
  std::array<double, kEndmemberCount> a{};

  // Replaces the fraction `alpha` (0..1) of the mixture by endmember k.
  void paint(int k, double alpha) {
    if (alpha <= 0.0) return;
    for (double& v : a) v *= 1.0 - alpha;
    a[k] += alpha;
  }

  Abundances toFloat() const {
    Abundances out;
    for (int k = 0; k < kEndmemberCount; ++k) out[k] = static_cast<float>(a[k]);
    return out;
  }
};

double noiseAt(std::uint64_t seed, const Eigen::Vector3d& p_W, double wavelength_m) {
  const double f = 1.0 / wavelength_m;
  return gradientNoise3(seed, p_W.x() * f, p_W.y() * f, p_W.z() * f);
}

}  // namespace

MaterialField::MaterialField(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  areas_seed_ = rng();
  algae_seed_ = rng();
  coral_seed_ = rng();
  grit_seed_ = rng();
  rock_grain_seed_ = rng();
  rock_algae_seed_ = rng();
  rock_sponge_seed_ = rng();
  rock_dust_seed_ = rng();
}

Abundances MaterialField::abundances(const Eigen::Vector3d& p_W, SurfaceKind kind) const {
  return kind == SurfaceKind::rock ? rock(p_W) : seabed(p_W);
}

Abundances MaterialField::seabed(const Eigen::Vector3d& p_W) const {
  Mixture m;
  // Metres: sand and sediment areas. Two octaves (3 m and 1.5 m) so that the
  // boundaries wander; the smoothstep makes them ~0.5 m wide.
  static constexpr FbmParameters kAreas{1.0 / 3.0, 2, 2.07, 0.5};
  // In plan view (north, east): at metre scale the seabed is a height field
  // (rocks have their own field), and 2D noise costs half of 3D on the
  // simulator's hottest path (this runs for every ray).
  const double areas = fbm2(areas_seed_, p_W.x(), p_W.y(), kAreas);
  const double sediment = smoothStep(-0.12, 0.12, areas);
  m.a[kSand] = 1.0 - sediment;
  m.a[kSediment] = sediment;

  // Centimetres: one noise at 1.4 cm gives both pebbles (its high values) and
  // shell grit (its low values), so they never overlap. Dark pebbles show on
  // sand, bright grit on sediment: either way ~15% of the ground is
  // high-contrast blobs with sharp (2-3 mm) edges.
  const double grit = noiseAt(grit_seed_, p_W, 0.02);
  m.paint(kRock, 0.85 * smoothStep(0.26, 0.30, grit));
  m.paint(kSand, 0.8 * smoothStep(0.26, 0.30, -grit));

  // Decimetres: algae tufts (more on sediment, where the threshold is lower)
  // and rarer coral/sponge patches.
  const double algae = noiseAt(algae_seed_, p_W, 0.22);
  const double algae_threshold = 0.27 - 0.2 * areas;
  m.paint(kAlgae, 0.9 * smoothStep(algae_threshold, algae_threshold + 0.04, algae));
  const double coral = noiseAt(coral_seed_, p_W, 0.16);
  m.paint(kCoral, 0.9 * smoothStep(0.31, 0.35, coral));
  return m.toFloat();
}

Abundances MaterialField::rock(const Eigen::Vector3d& p_W) const {
  Mixture m;
  m.a[kRock] = 1.0;
  // Metres: a dusting of sediment over parts of the rock.
  const double dust = noiseAt(rock_dust_seed_, p_W, 0.8);
  m.paint(kSediment, 0.45 * smoothStep(0.0, 0.3, dust));
  // Centimetres: light (quartz-like, sand spectrum) and dark mineral grains.
  const double grain = noiseAt(rock_grain_seed_, p_W, 0.012);
  m.paint(kSand, 0.55 * smoothStep(0.2, 0.26, grain));
  m.paint(kSediment, 0.5 * smoothStep(0.2, 0.26, -grain));
  // Decimetres: algae and encrusting sponge patches.
  const double algae = noiseAt(rock_algae_seed_, p_W, 0.15);
  m.paint(kAlgae, 0.85 * smoothStep(0.25, 0.29, algae));
  const double sponge = noiseAt(rock_sponge_seed_, p_W, 0.1);
  m.paint(kCoral, 0.8 * smoothStep(0.36, 0.4, sponge));
  return m.toFloat();
}

Eigen::MatrixXf MaterialField::endmemberMatrix(const std::vector<double>& wavelengths_nm) {
  Eigen::MatrixXf E(static_cast<Eigen::Index>(wavelengths_nm.size()), kEndmemberCount);
  for (std::size_t i = 0; i < wavelengths_nm.size(); ++i) {
    for (int k = 0; k < kEndmemberCount; ++k) {
      E(static_cast<Eigen::Index>(i), k) =
          static_cast<float>(endmemberReflectance(static_cast<Endmember>(k), wavelengths_nm[i]));
    }
  }
  return E;
}

}  // namespace hsmap
