#pragma once
// synthesizeIns: the nav/ins.csv a survey-grade INS would record along a
// VehicleTrajectory: fixes of B's position (lat, lon, depth) and attitude
// (roll, pitch, heading, degrees, ZYX body to NED; docs/SURVEY_FORMAT.md).
//
// Error model, per fix k at time t_k = t_begin + k / rate_hz:
//   position_W = p_W_B(t_k) + white_k + drift_k   (north, east, down, metres)
//     white_k ~ N(0, diag(h, h, d)^2)  (horizontal_noise_m, depth_noise_m)
//     drift_0 = 0, drift_k = drift_{k-1} + N(0, diag(h', h', d')^2 dt)
//       (h' = horizontal_drift_m_per_sqrt_s, d' = depth_drift_m_per_sqrt_s,
//       dt = 1 / rate_hz), a random walk: its standard deviation at time t
//       is h' sqrt(t - t_begin), the slow wander of a DVL-aided INS between
//       position resets;
//   attitude = roll/pitch/heading of R_W_B(t_k) + white noise
//     (roll_pitch_noise_deg, roll_pitch_noise_deg, heading_noise_deg).
// Position goes to geodetic coordinates through `w_frame`
// (LocalNedFrame::toGeodetic), so a fix converts back to W exactly.
// Roll and heading come from rollPitchHeadingDegFromQuaternion; after noise
// the heading is wrapped into [0, 360) (compass convention; ins.csv accepts
// [-180, 360]) and roll into (-180, 180].
//
// Randomness: std::mt19937_64(seed), nine standardNormal draws per fix in the
// order white north, east, down, drift north, east, down, roll, pitch,
// heading (drawn even when a sigma is zero, or when the attitude is not
// recorded), so the same seed always gives the same table, and changing one
// sigma or `attitude` does not reshuffle the others.
//
// attitude = false models an INS that gives positions only: the table has
// has_attitude = false (ins.csv without roll, pitch, heading columns) and
// its angles are 0; the positions are those of attitude = true.

#include <cstdint>

#include "core/geometry/local_ned_frame.h"
#include "core/survey/csv_table.h"
#include "pipelines/simulate/motion/vehicle_trajectory.h"

namespace hsmap {

struct InsNoiseConfig {
  double rate_hz = 1.0;                         // fixes per second, > 0
  double horizontal_noise_m = 0.3;              // white noise per axis (north, east), >= 0
  double horizontal_drift_m_per_sqrt_s = 0.02;  // random walk per axis, >= 0
  double depth_noise_m = 0.02;                  // >= 0
  double depth_drift_m_per_sqrt_s = 0.002;      // >= 0
  double roll_pitch_noise_deg = 0.05;           // >= 0
  double heading_noise_deg = 0.2;               // >= 0
  bool attitude = true;                         // false: fixes without roll, pitch, heading
  std::uint64_t seed = 1;

  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

// Fixes at t_begin + k / rate_hz for every k >= 0 with time <= t_end.
// has_attitude = noise.attitude. Throws std::invalid_argument for an invalid noise
// config or unless startTime() <= t_begin <= t_end <= endTime().
InsTable synthesizeIns(const VehicleTrajectory& trajectory, const InsNoiseConfig& noise,
                       const LocalNedFrame& w_frame, double t_begin, double t_end);

}  // namespace hsmap
