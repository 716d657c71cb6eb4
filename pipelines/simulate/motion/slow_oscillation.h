#pragma once
// SlowOscillation: a smooth, irregular-looking signal in [-1, 1] for the
// vehicle's slow motions (speed changes, roll, pitch, heading wander):
//   x(tau) = 0.7 sin(w_1 tau + phi_1) + 0.3 sin(w_2 tau + phi_2),
// with the periods 2 pi / w_i drawn uniformly from [min_period, max_period]
// and the phases from [0, 2 pi). Two sinusoids of unrelated periods do not
// repeat within a survey, yet the signal is C-infinity, bounded by 1 in
// absolute value (the weights sum to 1), and has closed-form derivative and
// integral (the integral gives arc length from a speed profile).
// The 0.7 / 0.3 split keeps the dominant period in charge, so the signal
// reaches at least 0.4 at every peak of the first term: an amplitude set in
// a configuration is actually seen.

#include <array>
#include <cmath>
#include <random>

#include "pipelines/simulate/motion/random_draws.h"

namespace hsmap {

class SlowOscillation {
 public:
  SlowOscillation() = default;

  // Draws two periods and two phases (four uniform01 draws, in that order).
  static SlowOscillation draw(std::mt19937_64& rng, double min_period_s, double max_period_s) {
    constexpr double kTwoPi = 6.283185307179586477;
    SlowOscillation oscillation;
    for (int i = 0; i < 2; ++i) {
      oscillation.omega_[i] = kTwoPi / uniformIn(rng, min_period_s, max_period_s);
      oscillation.phase_[i] = uniformIn(rng, 0.0, kTwoPi);
    }
    return oscillation;
  }

  double value(double tau) const {
    return kWeight[0] * std::sin(omega_[0] * tau + phase_[0]) +
           kWeight[1] * std::sin(omega_[1] * tau + phase_[1]);
  }

  // integral_0^tau x(tau') dtau'.
  double integral(double tau) const {
    double sum = 0.0;
    for (int i = 0; i < 2; ++i) {
      sum += kWeight[i] / omega_[i] * (std::cos(phase_[i]) - std::cos(omega_[i] * tau + phase_[i]));
    }
    return sum;
  }

 private:
  static constexpr std::array<double, 2> kWeight{0.7, 0.3};
  std::array<double, 2> omega_{0.0, 0.0};  // rad/s
  std::array<double, 2> phase_{0.0, 0.0};  // rad
};

}  // namespace hsmap
