#pragma once
// SensorNoise: the Gaussian noise of one image row or scan line, from a
// counter-based generator (splitmix64) and Marsaglia's polar method (exact
// normal pairs without trigonometry: it runs for every pixel and band).
//
// Why not std::normal_distribution over std::mt19937_64: seeding a Mersenne
// twister for every row costs more than the row's noise, and the standard
// distributions are implementation-defined, so the same seed would give
// different images with another standard library. splitmix64 is a fixed
// integer recipe: same seed, same bytes, everywhere.
#include <cmath>
#include <cstdint>

namespace hsmap {

class SensorNoise {
 public:
  explicit SensorNoise(std::uint64_t seed) : state_(seed) {}

  // A standard normal draw.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double x, y, s;
    do {
      x = 2.0 * uniform01() - 1.0;
      y = 2.0 * uniform01() - 1.0;
      s = x * x + y * y;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = y * scale;
    has_spare_ = true;
    return x * scale;
  }
  // A uniform draw in [0, 1).
  double uniform01() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace hsmap
