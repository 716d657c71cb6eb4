#include "pipelines/simulate/motion/vehicle_trajectory.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "core/geometry/so3.h"
#include "core/survey/number_text.h"

namespace hsmap {
namespace {

constexpr double kRadToDeg = 57.295779513082320877;

const VehicleMotionConfig& validated(const VehicleMotionConfig& config) {
  config.validate();
  return config;
}

LanePath makePath(const VehicleMotionConfig& config) {
  return LanePath(config.length_m, config.lanes, config.lane_spacing_m, config.start_north_m,
                  config.start_east_m, config.heading_deg);
}

}  // namespace

VehicleTrajectory::VehicleTrajectory(const VehicleMotionConfig& config,
                                     const std::function<double(double, double)>& seabed_z)
    : config_(validated(config)), path_(makePath(config_)), envelope_(path_, seabed_z) {
  std::mt19937_64 rng(config_.seed);
  speed_ = SlowOscillation::draw(rng, 20.0, 50.0);
  roll_ = SlowOscillation::draw(rng, 5.0, 9.0);
  pitch_ = SlowOscillation::draw(rng, 6.0, 11.0);
  heading_ = SlowOscillation::draw(rng, 25.0, 60.0);

  // Duration: the root of s(tau) = L. s is strictly increasing with slope in
  // [v0 (1 - a), v0 (1 + a)], which brackets the root; Newton converges in a
  // few steps and the bracket catches any overshoot.
  const double length = path_.length();
  const double v0 = config_.speed_m_s;
  const double a = config_.speed_variation;
  double low = length / (v0 * (1.0 + a));
  double high = length / (v0 * (1.0 - a));
  double tau = length / v0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double residual = arcLengthAtTau(tau) - length;
    if (residual > 0.0) high = tau; else low = tau;
    const double slope = v0 * (1.0 + a * speed_.value(tau));
    double next = tau - residual / slope;
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    const bool converged = std::abs(next - tau) <= 1e-13 * std::max(1.0, tau);
    tau = next;
    if (converged || high - low <= 1e-13 * std::max(1.0, tau)) break;
  }
  duration_s_ = tau;
}

double VehicleTrajectory::checkedTau(double t, const char* caller) const {
  if (!(t >= startTime() && t <= endTime())) {
    throw std::out_of_range(std::string("VehicleTrajectory::") + caller + ": time " +
                            formatDouble(t) + " s is outside the trajectory [" +
                            formatDouble(startTime()) + ", " + formatDouble(endTime()) + "] s");
  }
  return t - config_.start_time_s;
}

double VehicleTrajectory::arcLengthAtTau(double tau) const {
  return config_.speed_m_s * (tau + config_.speed_variation * speed_.integral(tau));
}

double VehicleTrajectory::arcLength(double t) const {
  return std::clamp(arcLengthAtTau(checkedTau(t, "arcLength")), 0.0, path_.length());
}

SE3d VehicleTrajectory::T_W_B(double t) const {
  const double tau = checkedTau(t, "T_W_B");
  const double s = std::clamp(arcLengthAtTau(tau), 0.0, path_.length());
  const PathPoint point = path_.at(s);
  const double roll_deg = config_.roll_pitch_amplitude_deg * roll_.value(tau);
  const double pitch_deg = config_.roll_pitch_amplitude_deg * pitch_.value(tau);
  const double heading_deg =
      point.heading_rad * kRadToDeg + config_.heading_wander_deg * heading_.value(tau);
  const Eigen::Vector3d p_W(point.north_m, point.east_m, envelope_.z(s) - config_.altitude_m);
  return SE3d(quaternionFromRollPitchHeadingDeg(roll_deg, pitch_deg, heading_deg), p_W);
}

}  // namespace hsmap
