#pragma once
// The start of geo-referencing: the similarity S_W_F that takes the
// front-end's frame F (arbitrary origin, orientation and scale) onto the
// world frame W of the INS, fitted on the camera positions at the INS fixes'
// own times.
//
// Pairs. For every fix whose time vision covers (camera_trajectory.h), the
// camera position p_F_C(t_fix) (interpolated between the frames around the
// fix, 33 ms apart at 30 fps, not taken from the nearest keyframe) and the
// INS camera position p_W_C = p_W_B + R_W_B t_B_C.
//
// Robustness. INS logs hold position jumps of metres. The pairs are first
// fitted with RANSAC (alignUmeyamaRobust, sim3.h) at a threshold of
// max(1 m, 4 sigma_horizontal): a fix beyond it is left out of the
// alignment and reported by its ins.csv line. Smaller faults are left to the
// bundle adjustment's test on each fix (georef_bundle_adjuster.h).
//
// Maximum likelihood. The RANSAC fit treats every axis alike, so its scale
// is decided by the horizontal positions (decimetres). From its inliers, a
// start is made with the rotation from the attitudes (the chordal mean of
// R_W_C(INS) R_F_C^T: a straight transect's positions leave the rotation
// about the track undetermined) and scale and translation from the
// positions (rotation_anchored_alignment.h); then the similarity is the
// maximum-likelihood fit of ins_similarity.h: depths and attitude weigh as
// their stated noise says, so on a short survey whose depth changes the
// depths decide the scale from the first alignment on. R_W_C(INS) =
// R_W_B R_B_C uses the INS attitude or, when the INS has none, the level,
// along-track attitude of ins_body_track.h.

#include <string>
#include <vector>

#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "core/survey/ins_body_track.h"
#include "pipelines/georef/camera_trajectory.h"
#include "pipelines/georef/ins_noise.h"
#include "solvers/similarity_fit.h"

namespace hsmap {

struct InsAlignment {
  Sim3 S_W_F;
  std::vector<int> paired_fixes;   // fix indices that vision covers
  std::vector<bool> inliers;       // per paired fix
  std::vector<double> residuals_m; // per paired fix: |p_W_C(INS) - S_W_F p_F_C|
  int inlier_count = 0;
  double rms_m = 0.0;              // camera-position residual over the inliers, metres
  double threshold_m = 0.0;
  std::string rotation_from;       // "INS attitude" or "level, along-track attitude (no INS attitude)"
  SimilarityFit fit;               // the maximum-likelihood fit on the inliers, with its covariance
};

// `vision_F`: the front-end's posed frames in F (no INS bridging).
// Throws std::runtime_error when fewer than 3 fixes fall within vision or no
// consistent similarity exists (naming how many pairs there were).
InsAlignment alignVisionToIns(const CameraTrajectory& vision_F, const InsBodyTrack& ins,
                              const SE3d& T_B_C, const InsNoise& noise);

}  // namespace hsmap
