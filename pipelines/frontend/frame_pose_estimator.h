#pragma once
// The pose T_F_C of one frame from landmarks it tracks:
//   1. PnP RANSAC (cv::solvePnPRansac, AP3P minimal samples) on the
//      undistorted normalised coordinates, which finds the pose and the gross
//      outliers (tracks that slid onto another corner);
//   2. a motion-only refinement with the engine: one pose variable, every
//      RANSAC inlier as a ReprojectionFactor on the distorted pixel with the
//      full lens model, landmarks held constant, a Huber loss so that the
//      inliers RANSAC let through at its threshold do not pull;
//   3. re-classification of every correspondence by its reprojection error
//      at the refined pose.
// `prediction` (the motion model's pose) is the fallback start when RANSAC
// cannot find a model, and the result must not be absurdly far from it.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/geometry/pinhole_radtan_camera.h"
#include "core/geometry/se3.h"

namespace hsmap {

struct PoseEstimatorOptions {
  double ransac_threshold_px = 2.0;
  int ransac_iterations = 100;
  double pixel_sigma_px = 1.0;
  double huber_scale = 2.0;
  int max_iterations = 5;
  int max_refined_points = 120;  // the refinement uses an even subsample of the inliers
  double inlier_threshold_px = 2.5;
  int min_inliers = 20;
  int solver_threads = 1;
};

struct PoseCorrespondence {
  Eigen::Vector3d p_F;
  Eigen::Vector2d normalized;  // undistorted x/z, y/z
  Eigen::Vector2d pixel;       // distorted, as measured
};

struct PoseEstimate {
  bool ok = false;
  std::string failure;
  SE3d T_F_C;
  std::vector<bool> inliers;  // per correspondence, after refinement
  int inlier_count = 0;
  int ransac_inliers = 0;
  double rms_error_px = 0.0;  // over the final inliers
};

PoseEstimate estimateFramePose(const std::vector<PoseCorrespondence>& correspondences,
                               const SE3d& prediction_T_F_C, const PinholeRadtanCamera& camera,
                               const PoseEstimatorOptions& options);

// Motion-only refinement alone (step 2): refines T_F_C in place over the
// correspondences flagged in `use`. Returns false when the solve is not usable.
bool refinePoseMotionOnly(const std::vector<PoseCorrespondence>& correspondences,
                          const std::vector<bool>& use, const PinholeRadtanCamera& camera,
                          const PoseEstimatorOptions& options, SE3d& T_F_C);

}  // namespace hsmap
