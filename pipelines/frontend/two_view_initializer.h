#pragma once
// Two-view initialisation of a monocular map (the start of a segment).
//
// Given the same points in two frames (undistorted normalised coordinates
// and the measured pixels), it
//   1. estimates the essential matrix by 5-point RANSAC (Nister 2004,
//      cv::findEssentialMat on normalised coordinates; the threshold is the
//      pixel threshold divided by the focal length);
//   2. decomposes it and picks, of the four (R, t), the one that puts the
//      most inliers in front of both cameras (cv::recoverPose);
//   3. triangulates every inlier (landmark_triangulator.h) and keeps the
//      points in front of both cameras with a small reprojection error;
//      then refines the second pose and the points by a two-view bundle
//      adjustment with the engine (the RANSAC model rests on five points);
//   4. accepts the start only if
//        - enough landmarks were made (a scene seen by few points is fragile),
//        - the fraction of RANSAC inliers in front of both cameras is high
//          (a wrong decomposition, e.g. the twin solution of a planar scene,
//          leaves about half the points behind a camera),
//        - their median parallax is large enough (with little parallax the
//          translation direction, and so the whole map, is unreliable).
// A failure says why, and the caller retries on a later frame.
//
// Scale: the map is scaled so that the median depth of the landmarks in the
// first camera is 1, which keeps numbers of order one whatever the altitude.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"

namespace hsmap {

struct TwoViewOptions {
  double ransac_threshold_px = 1.0;
  double max_error_px = 2.0;          // triangulation reprojection limit
  double min_parallax_rad = 0.035;    // median parallax of the landmarks (2 degrees)
  double min_point_parallax_rad = 0.0087;  // per landmark (0.5 degrees)
  int min_landmarks = 50;
  double min_cheirality_fraction = 0.9;
};

struct TwoViewResult {
  bool ok = false;
  std::string failure;  // why not, when !ok
  SE3d T_C1_C2;         // pose of the second camera in the first (median depth 1)
  // Per input pair: the landmark in C1's frame, or nullopt when rejected.
  std::vector<std::optional<Eigen::Vector3d>> p_C1;
  int ransac_inliers = 0;
  int landmarks = 0;
  double median_parallax_rad = 0.0;
};

TwoViewResult initializeTwoView(const std::vector<Eigen::Vector2d>& normalized1,
                                const std::vector<Eigen::Vector2d>& normalized2,
                                const std::vector<Eigen::Vector2d>& pixels1,
                                const std::vector<Eigen::Vector2d>& pixels2,
                                const PinholeRadtanCamera& camera, const TwoViewOptions& options);

}  // namespace hsmap
