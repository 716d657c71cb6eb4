#pragma once
// The maximum-likelihood similarity between two frames from positions and
// attitudes measured with stated, per-axis noise, and its covariance.
//
// This is how an INS places and scales a visual map (docs/GEOREF.md, "The
// map's scale and placement"): the map's shape is known to millimetres, the
// INS fixes to decimetres horizontally, centimetres in depth and hundredths
// of a degree in attitude, and the similarity S_T_S (source S: the map,
// target T: the INS's world) that best explains them is
//
//   min over (s, R, tau) of
//       sum_i |W_i (p_T,i - (s R (p_S,i - c) + tau + R l_S,i))|^2
//     + sum_k |A_k log(q_T,k^-1 R q_S,k)|^2
//
// with c the centroid of the source points, tau the image of c (the map's
// placement, nearly uncorrelated with the rotation however far the survey is
// from the origin), l_S,i an optional lever arm in metres on the source axes
// (it turns with the map but is not scaled: the INS measures its body, the
// map holds the camera, and the mounting is measured in metres), W_i and A_k
// the inverse 1-sigma per axis of the target's position (north, east, down)
// and of the attitude error (on the body's axes). The weights are what the
// survey states: a depth of 2 cm noise weighs 15 to 25 times more than a
// horizontal position of 0.3-0.5 m, so on a survey whose depth changes (a
// slope) the depths decide the scale, and the attitude decides the rotation
// (which a straight track's positions cannot).
//
// Solved with Ceres (7 unknowns: log s, a rotation increment theta with
// R = exp(theta) R0, tau) from a start the caller gives (e.g. a RANSAC
// Umeyama fit or the identity). The covariance is (J^T J)^-1 of the whitened
// residuals at the solution, on the minimal coordinates
//     (log s, theta about the target's axes, tau),
// so sigma_log_scale is the 1-sigma of the relative scale error. A direction
// the data leave free (a straight track without attitude leaves the roll
// about it) makes J^T J singular: `rank_deficient` says so, and the
// covariance is then the pseudo-inverse (the free direction carries no
// sigma); callers that need every direction add attitudes or priors.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/geometry/sim3.h"

namespace hsmap {

struct SimilarityFitPosition {
  Eigen::Vector3d p_source = Eigen::Vector3d::Zero();      // in S, S's units
  Eigen::Vector3d lever_source = Eigen::Vector3d::Zero();  // metres, on S's axes
  Eigen::Vector3d p_target = Eigen::Vector3d::Zero();      // measured, in T
  Eigen::Vector3d sigma_target = Eigen::Vector3d::Ones();  // per T axis, > 0
};

struct SimilarityFitAttitude {
  Eigen::Quaterniond q_source = Eigen::Quaterniond::Identity();  // R_S_B
  Eigen::Quaterniond q_target = Eigen::Quaterniond::Identity();  // measured R_T_B
  Eigen::Vector3d sigma_rad = Eigen::Vector3d::Ones();           // per body axis, > 0
};

struct SimilarityFit {
  Sim3 S_target_source;
  // Covariance on (log s, theta_x, theta_y, theta_z, tau_x, tau_y, tau_z).
  Eigen::Matrix<double, 7, 7> covariance = Eigen::Matrix<double, 7, 7>::Zero();
  double sigma_log_scale = 0.0;  // 1-sigma of the relative scale
  Eigen::Vector3d sigma_rotation_rad = Eigen::Vector3d::Zero();
  Eigen::Vector3d sigma_translation = Eigen::Vector3d::Zero();  // of tau, target units
  Eigen::Vector3d centroid_source = Eigen::Vector3d::Zero();    // c
  bool rank_deficient = false;
  double cost = 0.0;  // 1/2 the sum of squared whitened residuals
  int residuals = 0;
};

// Throws std::invalid_argument for a non-positive or non-finite sigma, fewer
// than 2 positions, or no solution (naming why).
SimilarityFit fitSimilarity(const std::vector<SimilarityFitPosition>& positions,
                            const std::vector<SimilarityFitAttitude>& attitudes,
                            const Sim3& start);

}  // namespace hsmap
