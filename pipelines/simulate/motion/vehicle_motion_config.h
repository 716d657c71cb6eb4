#pragma once
// VehicleMotionConfig: how the simulated vehicle moves over the scene
// (VehicleTrajectory turns it into poses). Units: metres, seconds, degrees;
// positions in W (local NED).
//
// Defaults describe a slow camera survey: one 20 m transect at 0.3 m/s, 2 m
// above the seabed, with the few degrees of roll, pitch and heading wander of
// a small ROV/AUV in calm water.

#include <cstdint>
#include <string>

namespace hsmap {

enum class MotionPattern {
  transect,   // one lane, heading `heading_deg` (north by default) from the start point
  lawnmower,  // `lanes` lanes alternating forward / back, stepping to the right of the
              // first lane (east when it heads north), joined by U-turns
};

struct VehicleMotionConfig {
  MotionPattern pattern = MotionPattern::transect;
  double length_m = 20.0;          // along-track length of the transect (of each lane), > 0
  double speed_m_s = 0.3;          // mean speed over ground, > 0
  double speed_variation = 0.2;    // relative amplitude of slow speed changes, in [0, 0.9]
  double altitude_m = 2.0;         // above the smoothed upper envelope of the seabed, > 0
  double roll_pitch_amplitude_deg = 3.0;  // bound of |roll| and |pitch|, in [0, 45]
  double heading_wander_deg = 3.0;        // bound of the body's yaw off the path, in [0, 45]
  int lanes = 1;                   // transect: 1; lawnmower: >= 2
  double lane_spacing_m = 2.0;     // east offset between lanes (lawnmower), > 0
  double heading_deg = 0.0;        // direction of the first lane, clockwise from north, in
                                   // [-360, 360]; the whole path turns about its start
  double start_north_m = 0.0;      // start of the first lane
  double start_east_m = 0.0;
  double start_time_s = 0.0;       // clock time at the start of the trajectory
  std::uint64_t seed = 1;

  // Throws std::invalid_argument naming the first field out of its range
  // (e.g. "VehicleMotionConfig: speed_variation must be in [0, 0.9], got 0.95").
  void validate() const;
};

// "transect" / "lawnmower".
std::string motionPatternName(MotionPattern pattern);
// Inverse of motionPatternName; throws std::invalid_argument for another name.
MotionPattern parseMotionPattern(const std::string& name);

}  // namespace hsmap
