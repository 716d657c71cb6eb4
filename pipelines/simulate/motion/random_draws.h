#pragma once
// Random draws for the motion and INS simulation that are bit-identical on
// every platform for a given std::mt19937_64 stream.
//
// std::uniform_real_distribution and std::normal_distribution are
// implementation-defined (libstdc++ and libc++ turn the same engine output
// into different numbers), so a survey simulated from a seed would change
// with the standard library. The engine itself is fully specified by the
// standard, and these draws use its raw output only:
//   uniform01:      the top 53 bits of one output, scaled into [0, 1);
//   standardNormal: Box-Muller on two uniform01 draws (one value per call,
//                   so the number of engine outputs per call is always 2).

#include <cmath>
#include <cstdint>
#include <random>

namespace hsmap {

// Uniform in [0, 1), from one engine output.
inline double uniform01(std::mt19937_64& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Uniform in [low, high).
inline double uniformIn(std::mt19937_64& rng, double low, double high) {
  return low + (high - low) * uniform01(rng);
}

// Standard normal N(0, 1), from two engine outputs.
inline double standardNormal(std::mt19937_64& rng) {
  constexpr double kTwoPi = 6.283185307179586477;
  // 1 - u is in (0, 1]: the logarithm stays finite.
  const double u1 = 1.0 - uniform01(rng);
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

}  // namespace hsmap
