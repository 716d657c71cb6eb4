#pragma once
// A synthetic scene for the front-end's unit tests: a camera looking down
// (C's z along W's down) at a gently rough seabed 2 m below, 640x480 with
// some lens distortion, and helpers to see its points from a pose.
#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"
#include "core/geometry/so3.h"

namespace hsmap::testing {

inline PinholeRadtanParameters syntheticIntrinsics() {
  PinholeRadtanParameters p;
  p.width = 640;
  p.height = 480;
  p.fx = 520.0;
  p.fy = 515.0;
  p.cx = 321.0;
  p.cy = 238.5;
  p.distortion = {-0.12, 0.03, 0.0005, -0.0003, 0.0};
  return p;
}

// Points on a rough surface at depth ~2 in front of the identity camera.
inline std::vector<Eigen::Vector3d> seabedPoints(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double x = 1.6 * u(rng), y = 1.2 * u(rng);
    points.emplace_back(x, y, 2.0 + 0.15 * std::sin(3.0 * x) * std::cos(2.0 * y) + 0.05 * u(rng));
  }
  return points;
}

// Pixel and undistorted normalised coordinates of p_F seen from T_F_C;
// false when behind or outside the image.
inline bool observe(const PinholeRadtanCamera& camera, const SE3d& T_F_C, const Eigen::Vector3d& p_F,
                    Eigen::Vector2d& pixel, Eigen::Vector2d& normalized) {
  const Eigen::Vector3d p_C = T_F_C.inverse() * p_F;
  if (p_C.z() <= 0.1) return false;
  pixel = camera.project(p_C);
  normalized = p_C.head<2>() / p_C.z();
  return camera.isInImage(pixel);
}

inline double rotationAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return logSO3(Eigen::Quaterniond(a.conjugate() * b)).norm() * 180.0 / M_PI;
}

}  // namespace hsmap::testing
