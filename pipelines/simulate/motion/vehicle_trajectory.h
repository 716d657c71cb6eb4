#pragma once
// VehicleTrajectory: the true, continuous pose T_W_B(t) of the simulated
// vehicle's body B (x forward, y starboard, z down) in W (local NED), built
// from a VehicleMotionConfig and the scene's seabed.
//
// Motion model (tau = t - start_time_s, all from closed forms or C2 splines,
// so the pose is C2 in t and a cubic B-spline can represent it):
//   - horizontal path: LanePath (a transect or lawnmower lanes joined by
//     smooth U-turns), followed exactly; arc length
//       s(tau) = v0 (tau + a * integral_0^tau x_v),  speed ds/dt = v0 (1 + a x_v(tau))
//     with v0 = speed_m_s, a = speed_variation and x_v a SlowOscillation
//     (periods 20-50 s), so the speed over ground stays in [v0 (1 - a), v0 (1 + a)];
//   - depth: z_B = Z(s) - altitude_m with Z the TerrainEnvelope (smoothed
//     upper envelope of the seabed within ~1 m, Hann-smoothed over ~2 m);
//   - attitude: R_W_B = Rz(heading) Ry(pitch) Rx(roll) (so3.h) with
//       heading = path heading + heading_wander_deg * x_h(tau)   (periods 25-60 s)
//       roll    = roll_pitch_amplitude_deg * x_r(tau)            (periods 5-9 s)
//       pitch   = roll_pitch_amplitude_deg * x_p(tau)            (periods 6-11 s)
//     The body yaws off the path (crab) but the path itself is kept, as a
//     vehicle holding its track line under a cross current does.
// The four oscillations are drawn from std::mt19937_64(seed) in the order
// speed, roll, pitch, heading: the same configuration and seabed give
// bit-identical poses.
//
// Cost: the constructor calls seabed_z at most TerrainEnvelopeOptions'
// max_queries (20000) times; T_W_B is allocation-free (a few sines, one
// spline lookup, a 20-node quadrature inside U-turns).

#include <functional>

#include "core/geometry/se3.h"
#include "pipelines/simulate/motion/lane_path.h"
#include "pipelines/simulate/motion/slow_oscillation.h"
#include "pipelines/simulate/motion/terrain_envelope.h"
#include "pipelines/simulate/motion/vehicle_motion_config.h"

namespace hsmap {

class VehicleTrajectory {
 public:
  // seabed_z(north, east): z_W (down) of the topmost scene surface there;
  // non-finite where there is none. Throws std::invalid_argument for an
  // invalid config (VehicleMotionConfig::validate) or a path with no seabed
  // under it (TerrainEnvelope).
  VehicleTrajectory(const VehicleMotionConfig& config,
                    const std::function<double(double north, double east)>& seabed_z);

  const VehicleMotionConfig& config() const { return config_; }
  const LanePath& path() const { return path_; }
  int seabedQueries() const { return envelope_.queries(); }

  double startTime() const { return config_.start_time_s; }
  double endTime() const { return config_.start_time_s + duration_s_; }

  // Arc length along the path at clock time t (metres, in [0, path().length()]).
  // Throws std::out_of_range outside [startTime(), endTime()].
  double arcLength(double t) const;

  // Pose of B in W at clock time t. Throws std::out_of_range outside
  // [startTime(), endTime()].
  SE3d T_W_B(double t) const;

 private:
  double checkedTau(double t, const char* caller) const;
  double arcLengthAtTau(double tau) const;

  VehicleMotionConfig config_;
  LanePath path_;
  TerrainEnvelope envelope_;
  SlowOscillation speed_;
  SlowOscillation roll_;
  SlowOscillation pitch_;
  SlowOscillation heading_;
  double duration_s_ = 0.0;
};

}  // namespace hsmap
