#pragma once
// A tie point of the extrinsic refinement (extrinsic_refinement.h, step 3):
// the UHI pixel (line, sample) saw the mesh point p_W. Made by the matching
// of the two ortho-images (ortho_matching.h), used by the T_C_U solve
// (extrinsic_from_tie_points.h) and the joint problem.

#include <Eigen/Core>

namespace hsmap {

// One association: UHI pixel (line, sample) saw the mesh point p_W.
struct ExtrinsicTiePoint {
  long long line = 0;  // the scan line nearest line_position
  // Continuous line coordinate of the UHI pixel that saw p_W (the ancillary
  // layer interpolated at the match): between two lines, the UHI saw p_W at
  // a time between theirs.
  double line_position = 0.0;
  double sample = 0.0;
  double range_m = 0.0;  // UHI range of the pixel (sets its noise); <= 0: 2 m
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  // Where it came from (diagnostics): RGB and hyperspectral grid positions, NCC.
  Eigen::Vector2d rgb_col_row = Eigen::Vector2d::Zero();
  Eigen::Vector2d hyper_col_row = Eigen::Vector2d::Zero();
  double ncc = 0.0;
};

}  // namespace hsmap
