#pragma once
// Triangulation of a landmark from two or more keyframes that saw it, with
// the checks that keep bad points out of the map:
//   - parallax: the largest angle between the viewing rays must reach
//     `min_angle_rad`; below it the depth is dominated by pixel noise (a
//     0.3 px error at 1 degree of parallax is ~2 % of the depth, and the
//     error grows as 1 / angle);
//   - cheirality: the point is in front of every camera;
//   - reprojection: in every view the point projects (with the lens model,
//     onto the distorted pixel as measured) within `max_error_px`.
//
// The point is the linear (DLT) solution of Hartley & Zisserman (sec. 12.2)
// on the undistorted normalised coordinates, rows scaled to unit rays so
// that no view dominates: for view i with T_C_F = [R | t] and ray x,
//     x_i cross (R p + t) = 0   (two independent rows per view),
// solved for homogeneous p by SVD.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"

namespace hsmap {

// One view of the point: the camera pose, the undistorted normalised
// coordinates of the measurement (x/z, y/z) and the measured pixel.
struct TriangulationView {
  SE3d T_F_C;
  Eigen::Vector2d normalized = Eigen::Vector2d::Zero();
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
};

struct TriangulationLimits {
  double min_angle_rad = 0.026;  // 1.5 degrees
  double max_error_px = 2.0;
};

enum class TriangulationOutcome { ok, low_parallax, behind_camera, reprojection, degenerate };
const char* toString(TriangulationOutcome outcome);

struct TriangulationResult {
  TriangulationOutcome outcome = TriangulationOutcome::degenerate;
  Eigen::Vector3d p_F = Eigen::Vector3d::Zero();
  double parallax_rad = 0.0;     // largest angle between two rays
  double max_error_px = 0.0;     // worst reprojection error over the views
  bool ok() const { return outcome == TriangulationOutcome::ok; }
};

// The linear triangulation alone (no checks); std::nullopt when degenerate
// (fewer than two views, or a point at infinity).
std::optional<Eigen::Vector3d> triangulateLinear(const std::vector<TriangulationView>& views);

// Largest angle between the rays from the views' centres to p_F, and between
// the measured rays themselves (before a point exists).
double rayParallax(const std::vector<TriangulationView>& views);

TriangulationResult triangulateLandmark(const std::vector<TriangulationView>& views,
                                        const PinholeRadtanCamera& camera,
                                        const TriangulationLimits& limits);

}  // namespace hsmap
