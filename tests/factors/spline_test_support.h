#pragma once
// Shared by the spline factors' tests: a turning, wobbling trajectory spline
// and the parameter blocks of a segment's four active control points.

#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/se3_bspline.h"
#include "tests/factors/factor_test_support.h"

namespace hsmap::test {

// Control points of a turning, wobbling motion from t0, each perturbed.
inline SE3Splined wobblyTrajectory(std::mt19937& rng, double t0, double dt, int num_control_points) {
  std::vector<SE3d> control_points;
  for (int k = 0; k < num_control_points; ++k) {
    const double t = t0 + (k - 1) * dt;
    const SE3d nominal(expSO3(Eigen::Vector3d(0.2 * std::sin(3.0 * t), 0.1 * std::cos(2.0 * t),
                                              0.3 * t)),
                       Eigen::Vector3d(1.5 * t, 0.4 * std::sin(t), 10.0 + 0.2 * t));
    control_points.push_back(nominal * randomPose(rng, 0.05, 0.03));
  }
  return SE3Splined(t0, dt, control_points);
}

// The blocks S(i) .. S(i+3) of a segment.
inline std::vector<ParameterBlock> segmentState(const SE3Splined& spline, const SplineSegment& segment) {
  std::vector<ParameterBlock> blocks;
  for (int k = 0; k < 4; ++k) {
    blocks.push_back(poseBlock(spline.controlPoints()[std::size_t(segment.first_control_point + k)]));
  }
  return blocks;
}

}  // namespace hsmap::test
