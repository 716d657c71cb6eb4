#pragma once
// A small geo-referencing scene for the stage's unit tests: a camera looking
// down from 2 m above a rough seabed, the vehicle sweeping a 12 m curve at
// 0.4 m/s for 30 s, its INS at 1 Hz (body = camera through a known T_B_C),
// and the same trajectory in a front-end frame F = S_F_W * W.

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "core/geometry/so3.h"
#include "core/survey/ins_body_track.h"

namespace hsmap::georef_testing {

// The scene's RGB camera: 640 x 480, f 500 px, a little barrel distortion.
inline PinholeRadtanParameters testCamera() {
  PinholeRadtanParameters p;
  p.width = 640;
  p.height = 480;
  p.fx = p.fy = 500.0;
  p.cx = 320.0;
  p.cy = 240.0;
  p.distortion = {-0.05, 0.01, 0.0, 0.0, 0.0};
  return p;
}

inline SE3d mountingT_B_C() {
  // Camera x to starboard (body y), looking down (body z), 0.5 m forward.
  return SE3d(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
              Eigen::Vector3d(0.5, 0.0, 0.3));
}

// The true body pose at t in [0, 30]: a gentle S-curve at 0.4 m/s, heading
// following the track, with a little roll and pitch.
inline SE3d trueBody(double t) {
  const double x = 0.4 * t;
  const double y = 1.5 * std::sin(0.15 * t);
  const double heading = std::atan2(1.5 * 0.15 * std::cos(0.15 * t), 0.4);
  const Eigen::Quaterniond q = quaternionFromRollPitchHeadingDeg(
      2.0 * std::sin(0.7 * t), 1.5 * std::cos(0.5 * t), heading * 180.0 / M_PI);
  return SE3d(q, Eigen::Vector3d(x, y, 8.0 + 0.1 * std::sin(0.3 * t)));
}

inline SE3d trueCamera(double t) { return trueBody(t) * mountingT_B_C(); }

// The front-end's arbitrary frame: F = S_F_W W.
inline Sim3 trueS_W_F() {
  return Sim3(3.7, Eigen::Quaterniond(Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized())),
              Eigen::Vector3d(4.0, -2.0, 7.0));
}

// INS fixes at 1 Hz with white noise; `jumps` adds a displacement to fix i.
inline std::vector<InsBodyFix> insFixes(double sigma_h, double sigma_d, unsigned seed,
                                           const std::vector<std::pair<int, Eigen::Vector3d>>& jumps = {}) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<InsBodyFix> fixes;
  for (int i = 0; i <= 30; ++i) {
    InsBodyFix fix;
    fix.t = double(i);
    const SE3d T = trueBody(fix.t);
    fix.p_W_B = T.t + Eigen::Vector3d(sigma_h * unit(rng), sigma_h * unit(rng), sigma_d * unit(rng));
    fix.q_W_B = T.q;
    fix.line_number = i + 2;
    for (const auto& [index, jump] : jumps) {
      if (index == i) fix.p_W_B += jump;
    }
    fixes.push_back(fix);
  }
  return fixes;
}

inline double angleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return logSO3(Eigen::Quaterniond(a.conjugate() * b)).norm() * 180.0 / M_PI;
}

}  // namespace hsmap::georef_testing
