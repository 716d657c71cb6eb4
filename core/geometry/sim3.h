#pragma once
// Sim3: a similarity transform S_B_A = (s, q, t) between two frames A and B,
//     p_B = S_B_A * p_A = s * R(q) * p_A + t,        s > 0,
// with q a unit quaternion (Eigen's convention, as in se3.h) and t the origin
// of A expressed in B. The monocular front-end builds its map in a vision
// frame V whose scale and placement are arbitrary; the INS stage finds the
// S_W_V that brings it onto the local NED frame W (docs/ENGINE.md).
//
// Group operations (the 4x4 matrix [s R, t; 0, 1] is the reference):
//   compose  S_C_A = S_C_B * S_B_A = (s1 s2, q1 q2, s1 R1 t2 + t1)
//   inverse  S_A_B = (1/s, q^-1, -(1/s) R^-1 t)
//
// Camera poses. A pose T_A_C (camera C in A) re-expressed in B is
//     transformPose(T_A_C) = T_B_C = (q * q_A_C, s R t_A_C + t):
// the camera's centre moves like any point and its axes turn by R; the scale
// is not a rigid motion, so it cannot live in the SE(3) result. Points of
// the camera frame then map as p_B = S_B_A * (T_A_C * p_C) = T_B_C * (s p_C):
// depths measured in A's units grow by s, which is what re-scaling a
// monocular map means.
//
// Alignment. alignUmeyama() finds the S_B_A that maps the source points
// (in A) onto the target points (in B) in least squares,
//     min over (s, R, t) of  sum_i | target_i - (s R source_i + t) |^2,
// in closed form (Umeyama, "Least-squares estimation of transformation
// parameters between two point patterns", PAMI 1991) through Eigen::umeyama.
// The solution is unique when the centred source points span at least a
// plane (a flat seabed is fine); all-equal or collinear sources leave the
// rotation about their line free and are rejected.
//
// alignUmeyamaRobust() does the same with gross outliers among the pairs:
// RANSAC over minimal 3-point samples, a least-squares refit on the largest
// consensus set, one re-classification of every pair against the refit (see
// the function's comment for the numbers and the determinism).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "core/geometry/se3.h"

namespace hsmap {

class Sim3 {
 public:
  // The identity (s = 1, no rotation, no translation).
  Sim3();
  // Throws std::invalid_argument unless scale is finite and > 0 and the
  // rotation and translation are finite; the quaternion is normalised.
  Sim3(double scale, const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation);

  static Sim3 identity() { return Sim3(); }

  double scale() const { return s_; }
  const Eigen::Quaterniond& rotation() const { return q_; }
  const Eigen::Vector3d& translation() const { return t_; }
  // [s R, t; 0, 1].
  Eigen::Matrix4d matrix() const;

  // p_B = s R p_A + t.
  Eigen::Vector3d apply(const Eigen::Vector3d& p_A) const { return s_ * (q_ * p_A) + t_; }
  // S_C_A = (*this = S_C_B) * S_B_A.
  Sim3 operator*(const Sim3& S_B_A) const;
  Sim3 inverse() const;
  // T_B_C = (q q_A_C, s R t_A_C + t) for a camera pose T_A_C (see the header comment).
  SE3d transformPose(const SE3d& T_A_C) const;

 private:
  double s_;
  Eigen::Quaterniond q_;
  Eigen::Vector3d t_;
};

// The S_B_A minimising sum_i |target_i - S_B_A * source_i|^2 (source_i in A,
// target_i in B, pairs by index). With estimate_scale == false the scale is
// fixed to 1 (a rigid alignment, for frames already in metres).
// Throws std::invalid_argument when the sizes differ, there are fewer than 3
// pairs, a point is not finite, or the source points coincide or are
// collinear (the rotation about their line is then undetermined); the same
// for the target points, for the same reason (and a collapsed target would
// give a scale of 0). "Collinear" means to within rounding (the second
// principal extent below 1e-8 of the first): nearly collinear points, e.g.
// the camera centres of a straight transect, are accepted, and their roll
// about the line is then only as good as their sideways spread allows.
Sim3 alignUmeyama(const std::vector<Eigen::Vector3d>& source,
                  const std::vector<Eigen::Vector3d>& target, bool estimate_scale = true);

struct RobustAlignment {
  // S_B_A: the least-squares fit of the RANSAC consensus set.
  Sim3 sim3;
  // inliers[i]: |target_i - sim3.apply(source_i)| <= inlier_threshold.
  std::vector<bool> inliers;
  std::size_t inlier_count = 0;
  // RMS of |target_i - sim3.apply(source_i)| over the inliers, in B's units.
  double inlier_rms = 0.0;
};

// RANSAC settings of alignUmeyamaRobust(), fixed so that a run is
// reproducible. 500 minimal samples find an all-inlier one with probability
// 1 - (1 - w^3)^500: > 1 - 1e-28 for an inlier fraction w = 0.5, 0.9999990
// for w = 0.3. The seed feeds std::mt19937, whose output the C++ standard
// fixes, and the indices are drawn from it without a distribution object, so
// the samples are the same with every standard library.
inline constexpr int kRobustAlignmentIterations = 500;
inline constexpr unsigned kRobustAlignmentSeed = 20240607u;

// alignUmeyama() in the presence of gross outliers among the pairs.
//   1. RANSAC: kRobustAlignmentIterations minimal samples of 3 distinct
//      pairs; samples whose source (or, with the scale estimated, target)
//      triangle is nearly degenerate are skipped; each model scores the
//      pairs with |target_i - S source_i| <= inlier_threshold (most inliers
//      wins, ties go to the smaller sum of squared inlier errors).
//   2. The least-squares alignUmeyama() on the best consensus set.
//   3. One re-classification of every pair against that refit, which gives
//      inliers, inlier_count and inlier_rms (all relative to the returned
//      sim3; a borderline pair may change side between steps 1 and 3).
// inlier_threshold is a distance in B's units (metres for W).
// Throws std::invalid_argument for the input errors of alignUmeyama() (the
// whole source being degenerate included) and a threshold that is not a
// finite number > 0; std::runtime_error when no sample gathers 3 inliers
// that span a plane (nothing agrees: the data cannot be aligned).
RobustAlignment alignUmeyamaRobust(const std::vector<Eigen::Vector3d>& source,
                                   const std::vector<Eigen::Vector3d>& target,
                                   double inlier_threshold, bool estimate_scale = true);

}  // namespace hsmap
