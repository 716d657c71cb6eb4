#include "pipelines/simulate/motion/ins_synthesis.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "core/geometry/so3.h"
#include "core/survey/number_text.h"
#include "pipelines/simulate/motion/random_draws.h"

namespace hsmap {
namespace {

void requireNonNegative(double value, const char* name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("InsNoiseConfig: ") + name +
                                " must be a finite number >= 0, got " + formatDouble(value));
  }
}

// Into [0, 360). fmod keeps the sign of its argument; a tiny negative input
// plus 360 can round to exactly 360, which is folded back to 0.
double wrapHeadingDeg(double heading_deg) {
  double wrapped = std::fmod(heading_deg, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

// Into (-180, 180].
double wrapRollDeg(double roll_deg) {
  const double wrapped = 180.0 - wrapHeadingDeg(180.0 - roll_deg);
  return wrapped <= -180.0 ? 180.0 : wrapped;
}

}  // namespace

void InsNoiseConfig::validate() const {
  if (!(rate_hz > 0.0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument("InsNoiseConfig: rate_hz must be a finite number > 0, got " +
                                formatDouble(rate_hz));
  }
  requireNonNegative(horizontal_noise_m, "horizontal_noise_m");
  requireNonNegative(horizontal_drift_m_per_sqrt_s, "horizontal_drift_m_per_sqrt_s");
  requireNonNegative(depth_noise_m, "depth_noise_m");
  requireNonNegative(depth_drift_m_per_sqrt_s, "depth_drift_m_per_sqrt_s");
  requireNonNegative(roll_pitch_noise_deg, "roll_pitch_noise_deg");
  requireNonNegative(heading_noise_deg, "heading_noise_deg");
}

InsTable synthesizeIns(const VehicleTrajectory& trajectory, const InsNoiseConfig& noise,
                       const LocalNedFrame& w_frame, double t_begin, double t_end) {
  noise.validate();
  if (!(t_begin >= trajectory.startTime() && t_begin <= t_end && t_end <= trajectory.endTime())) {
    throw std::invalid_argument(
        "synthesizeIns: expected startTime() <= t_begin <= t_end <= endTime() = " +
        formatDouble(trajectory.startTime()) + " <= " + formatDouble(t_begin) + " <= " +
        formatDouble(t_end) + " <= " + formatDouble(trajectory.endTime()));
  }
  std::mt19937_64 rng(noise.seed);
  const double dt = 1.0 / noise.rate_hz;
  const double drift_step_horizontal = noise.horizontal_drift_m_per_sqrt_s * std::sqrt(dt);
  const double drift_step_depth = noise.depth_drift_m_per_sqrt_s * std::sqrt(dt);

  InsTable table;
  table.has_attitude = noise.attitude;
  Eigen::Vector3d drift_W = Eigen::Vector3d::Zero();
  for (long long k = 0;; ++k) {
    // Times from k, not by accumulating dt, so that rounding does not build up.
    const double t = t_begin + static_cast<double>(k) / noise.rate_hz;
    if (t > t_end) break;
    const Eigen::Vector3d white_W(noise.horizontal_noise_m * standardNormal(rng),
                                  noise.horizontal_noise_m * standardNormal(rng),
                                  noise.depth_noise_m * standardNormal(rng));
    const Eigen::Vector3d drift_step_W(drift_step_horizontal * standardNormal(rng),
                                       drift_step_horizontal * standardNormal(rng),
                                       drift_step_depth * standardNormal(rng));
    // The walk starts at zero at the first fix (the INS was just aligned).
    if (k > 0) drift_W += drift_step_W;
    const double roll_noise = noise.roll_pitch_noise_deg * standardNormal(rng);
    const double pitch_noise = noise.roll_pitch_noise_deg * standardNormal(rng);
    const double heading_noise = noise.heading_noise_deg * standardNormal(rng);

    const SE3d T_W_B = trajectory.T_W_B(t);
    const GeodeticPoint position = w_frame.toGeodetic(T_W_B.t + white_W + drift_W);
    const Eigen::Vector3d attitude_deg = rollPitchHeadingDegFromQuaternion(T_W_B.q);

    InsFix fix;
    fix.t = t;
    fix.lat_deg = position.lat_deg;
    fix.lon_deg = position.lon_deg;
    fix.depth_m = position.depth_m;
    if (noise.attitude) {
      fix.roll_deg = wrapRollDeg(attitude_deg[0] + roll_noise);
      // Pitch is a few degrees here; clamping only guards the +-90 range ins.csv enforces.
      fix.pitch_deg = std::clamp(attitude_deg[1] + pitch_noise, -90.0, 90.0);
      fix.heading_deg = wrapHeadingDeg(attitude_deg[2] + heading_noise);
    }
    table.fixes.push_back(fix);
  }
  return table;
}

}  // namespace hsmap
