#pragma once
// Alignment when the rotation is known better than the positions can give it.
//
// A vehicle's INS measures attitude to a tenth of a degree but positions only
// to decimetres, and a straight transect's positions are nearly collinear,
// which leaves the rotation about the track undetermined by a point fit
// (alignUmeyama, sim3.h). So the rotation comes from the attitudes and only
// scale and translation from the positions:
//
// chordalMeanRotation(): the rotation R minimising sum_i |R - R_i|_F^2 (the
//   chordal L2 mean; Hartley et al., "Rotation averaging", IJCV 2013): the
//   projection of sum_i R_i onto SO(3) by SVD. Throws std::invalid_argument
//   for no rotations or a sum whose projection is not unique (rotations that
//   cancel out).
//
// alignScaleTranslation(): given q_B_A, the s > 0 and t minimising
//   sum_i |target_i - (s R source_i + t)|^2 in closed form. Throws
//   std::invalid_argument for fewer than 2 pairs, sizes that differ, or a
//   source (or a target) that does not move along the rotated source: then
//   no positive scale fits.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/geometry/sim3.h"

namespace hsmap {

Eigen::Quaterniond chordalMeanRotation(const std::vector<Eigen::Quaterniond>& rotations);

Sim3 alignScaleTranslation(const Eigen::Quaterniond& q_B_A,
                           const std::vector<Eigen::Vector3d>& source,
                           const std::vector<Eigen::Vector3d>& target);

}  // namespace hsmap
