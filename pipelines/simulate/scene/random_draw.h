#pragma once
// uniformDraw: a uniform double in [lo, hi) from a std::mt19937_64, computed
// here rather than with std::uniform_real_distribution, whose algorithm is
// left to each standard library: scenes must be identical for one seed on
// every platform, not only with one library.

#include <random>

namespace hsmap {

inline double uniformDraw(std::mt19937_64& rng, double lo, double hi) {
  // The top 53 bits as a fraction in [0, 1).
  const double unit = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return lo + (hi - lo) * unit;
}

}  // namespace hsmap
