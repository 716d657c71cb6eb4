#pragma once
// Seeded gradient noise (Perlin's construction) in 2D and 3D, and fractal sums
// of it, for the simulator's terrain, rock shapes and material patterns.
//
// Contract:
//   - every function is a pure function of (seed, position): no mutable state,
//     so any thread may call it and the same seed always gives bit-identical
//     values (the simulator's determinism rests on this); any two seeds, even
//     consecutive ones, give independent-looking fields (the seed is mixed
//     through a full 64-bit finaliser once per call);
//   - gradientNoise2/3 have unit lattice spacing; they are 0 at every lattice
//     point, C2-continuous (quintic fade), zero-mean, and bounded by sqrt(N)/2
//     for N dimensions (unit gradients): |n| <= 0.71 in 2D, <= 0.87 in 3D;
//   - their standard deviation is about 0.22 (2D) and 0.19 (3D), so thresholds
//     select area fractions roughly as on a normal distribution (n > 0.2 covers
//     about 15% of the 3D field).
//
// Lattice hashing: corner (i, j, k) -> a linear combination with odd 64-bit
// constants plus the mixed seed, then one xor-shift and one multiply, whose top
// bits pick the gradient. The linear combination only repeats for lattice
// offsets of about 2^21 cells, far beyond any survey extent at the
// frequencies used.
//
// fbm (fractional Brownian motion): the sum of `octaves` copies at frequencies
// f, f*l, f*l^2, ... with amplitudes 1, g, g^2, ..., normalised by the sum of
// the amplitudes so the result stays in about the range of one octave. Each
// octave gets its own seed, and lacunarity is not exactly 2 by default, so the
// lattice points of different octaves do not line up (they would leave a
// visible grid of zeros).

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace hsmap {

namespace noise_detail {

inline std::uint64_t finalize64(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

// The corner hash needs only its top 4 bits to be well mixed (they pick the
// gradient): one xor-shift folds the high bits of the linear combination into
// the low ones and one multiply spreads every bit into the top ones: cheaper
// than a full finaliser, and noise3 makes 8 of these per call.
inline std::uint64_t hashCorner(std::uint64_t seed, std::int64_t i, std::int64_t j,
                                std::int64_t k) {
  std::uint64_t h = seed + static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ULL +
                    static_cast<std::uint64_t>(j) * 0xd6e8feb86659fd93ULL +
                    static_cast<std::uint64_t>(k) * 0xa0761d6478bd642fULL;
  h ^= h >> 32;
  return h * 0xe7037ed1a0b428dbULL;
}

// 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at 0 and 1.
inline double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

inline double lerp(double a, double b, double t) { return a + t * (b - a); }

// Dot product of one of 12 cube-edge directions (+-1, +-1, 0) and
// permutations, scaled to unit length, with d. 4 hash bits pick one of 16
// table rows: the 12 edges plus 4 of them repeated (as in Perlin's 2002
// noise). A table rather than branches: the choice is random, so branches
// would often be mispredicted.
inline constexpr double kEdge = 0.7071067811865476;
inline constexpr double kGradients3[16][3] = {
    {kEdge, kEdge, 0}, {-kEdge, kEdge, 0}, {kEdge, -kEdge, 0}, {-kEdge, -kEdge, 0},
    {kEdge, 0, kEdge}, {-kEdge, 0, kEdge}, {kEdge, 0, -kEdge}, {-kEdge, 0, -kEdge},
    {0, kEdge, kEdge}, {0, -kEdge, kEdge}, {0, kEdge, -kEdge}, {0, -kEdge, -kEdge},
    {kEdge, kEdge, 0}, {-kEdge, kEdge, 0}, {0, -kEdge, kEdge}, {0, -kEdge, -kEdge}};
inline constexpr double kGradients2[8][2] = {{1, 0},          {-1, 0},         {0, 1},
                                             {0, -1},         {kEdge, kEdge},  {kEdge, -kEdge},
                                             {-kEdge, kEdge}, {-kEdge, -kEdge}};

inline double gradientDot3(std::uint64_t h, double dx, double dy, double dz) {
  const double* g = kGradients3[h >> 60];
  return g[0] * dx + g[1] * dy + g[2] * dz;
}

// One of 8 unit gradients (axes and diagonals) dotted with d.
inline double gradientDot2(std::uint64_t h, double dx, double dy) {
  const double* g = kGradients2[h >> 61];
  return g[0] * dx + g[1] * dy;
}

}  // namespace noise_detail

// Gradient noise at (x, y), unit lattice spacing.
inline double gradientNoise2(std::uint64_t seed, double x, double y) {
  using namespace noise_detail;
  seed = finalize64(seed);
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  const double dx = x - fx, dy = y - fy;
  const double n00 = gradientDot2(hashCorner(seed, i, j, 0), dx, dy);
  const double n10 = gradientDot2(hashCorner(seed, i + 1, j, 0), dx - 1.0, dy);
  const double n01 = gradientDot2(hashCorner(seed, i, j + 1, 0), dx, dy - 1.0);
  const double n11 = gradientDot2(hashCorner(seed, i + 1, j + 1, 0), dx - 1.0, dy - 1.0);
  const double u = fade(dx), v = fade(dy);
  return lerp(lerp(n00, n10, u), lerp(n01, n11, u), v);
}

// Gradient noise at p, unit lattice spacing.
inline double gradientNoise3(std::uint64_t seed, double x, double y, double z) {
  using namespace noise_detail;
  seed = finalize64(seed);
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy),
             k = static_cast<std::int64_t>(fz);
  const double dx = x - fx, dy = y - fy, dz = z - fz;
  const double n000 = gradientDot3(hashCorner(seed, i, j, k), dx, dy, dz);
  const double n100 = gradientDot3(hashCorner(seed, i + 1, j, k), dx - 1.0, dy, dz);
  const double n010 = gradientDot3(hashCorner(seed, i, j + 1, k), dx, dy - 1.0, dz);
  const double n110 = gradientDot3(hashCorner(seed, i + 1, j + 1, k), dx - 1.0, dy - 1.0, dz);
  const double n001 = gradientDot3(hashCorner(seed, i, j, k + 1), dx, dy, dz - 1.0);
  const double n101 = gradientDot3(hashCorner(seed, i + 1, j, k + 1), dx - 1.0, dy, dz - 1.0);
  const double n011 = gradientDot3(hashCorner(seed, i, j + 1, k + 1), dx, dy - 1.0, dz - 1.0);
  const double n111 =
      gradientDot3(hashCorner(seed, i + 1, j + 1, k + 1), dx - 1.0, dy - 1.0, dz - 1.0);
  const double u = fade(dx), v = fade(dy), w = fade(dz);
  const double nx00 = lerp(n000, n100, u), nx10 = lerp(n010, n110, u);
  const double nx01 = lerp(n001, n101, u), nx11 = lerp(n011, n111, u);
  return lerp(lerp(nx00, nx10, v), lerp(nx01, nx11, v), w);
}

inline double gradientNoise3(std::uint64_t seed, const Eigen::Vector3d& p) {
  return gradientNoise3(seed, p.x(), p.y(), p.z());
}

// Seed of octave `octave` of a fractal sum seeded with `seed`.
inline std::uint64_t octaveSeed(std::uint64_t seed, int octave) {
  return noise_detail::finalize64(seed ^
                                  (0x632be59bd9b4e019ULL * static_cast<std::uint64_t>(octave + 1)));
}

struct FbmParameters {
  double frequency = 1.0;  // of the first octave, cycles per unit of the input
  int octaves = 3;
  double lacunarity = 1.98;  // frequency ratio of successive octaves
  double gain = 0.5;         // amplitude ratio of successive octaves
};

inline double fbm2(std::uint64_t seed, double x, double y, const FbmParameters& f) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, frequency = f.frequency;
  for (int o = 0; o < f.octaves; ++o) {
    sum += amplitude * gradientNoise2(octaveSeed(seed, o), x * frequency, y * frequency);
    total += amplitude;
    amplitude *= f.gain;
    frequency *= f.lacunarity;
  }
  return sum / total;
}

inline double fbm3(std::uint64_t seed, const Eigen::Vector3d& p, const FbmParameters& f) {
  double sum = 0.0, amplitude = 1.0, total = 0.0, frequency = f.frequency;
  for (int o = 0; o < f.octaves; ++o) {
    sum += amplitude * gradientNoise3(octaveSeed(seed, o), p.x() * frequency, p.y() * frequency,
                                      p.z() * frequency);
    total += amplitude;
    amplitude *= f.gain;
    frequency *= f.lacunarity;
  }
  return sum / total;
}

// 0 below edge0, 1 above edge1, cubic in between (edge0 < edge1).
inline double smoothStep(double edge0, double edge1, double x) {
  double t = (x - edge0) / (edge1 - edge0);
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace hsmap
