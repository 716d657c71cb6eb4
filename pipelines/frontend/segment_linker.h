#pragma once
// Linking map segments through the INS.
//
// After a tracking loss the front-end starts a new map segment in a frame of
// its own (its own origin, orientation and scale). To pose the frames after
// the gap in the front-end's frame F (the frame of the reference segment,
// normally the first), each segment S is fitted to the INS: its keyframes'
// camera positions p_S against the INS camera positions p_W at the same
// times, which gives a similarity S_W_S; then
//     S_F_S = S_W_F^-1 * S_W_S
// takes the segment into F. The fit of F itself is part of the link, so its
// error enters both sides.
//
// INS camera positions. The INS body track (core/survey/ins_body_track.h):
// each fix converted to local NED W at the survey's origin, the body
// position and attitude interpolated at the keyframe time (linear / slerp
// between the 1 Hz fixes); then the lever arm is added:
//     p_W_C = p_W_B + R_W_B t_B_C           (T_B_C = survey.config.ins.T_B_C).
// When the INS has no attitude, R_W_B is taken from the fit itself:
// R_W_B = R_W_C R_B_C^T with R_W_C = R_W_S R_S_C, the fit repeated twice; the
// track's along-track heading is not needed then, and not derived
// (kSegmentLinkerInsOptions).
//
// The fit. With INS attitude, the rotation R_W_S is the chordal mean of
// R_W_C(INS) R_S_C^T over the keyframes (attitude is good to a tenth of a
// degree, positions only to decimetres, and a straight transect's positions
// are nearly collinear, which leaves the rotation about the track undetermined
// from positions alone), then scale and translation by least squares on the
// positions given that rotation. Without attitude, a full Umeyama fit on the
// positions (core/geometry/sim3.h), which needs a track that is not a line.
//
// Robustness. A faulty fix (a position jump of metres) must not pull the
// fit: the keyframe/INS pairs are first classified by a RANSAC Sim(3) on the
// positions (alignUmeyamaRobust, core/geometry/sim3.h) at `outlier_threshold_m`
// (the runner gives max(1 m, 4 sigma_horizontal)); the pairs it leaves out do
// not enter the fit above. When the positions are too nearly collinear for
// its minimal samples (a ruler-straight track) every pair is kept and the
// fit says so (SegmentFit::note).
//
// Scale 1-sigma: the least-squares standard error of the scale given the
// rotation, sigma_s = sigma / sqrt(sum_i |R (p_S,i - mean p_S)|^2), with
// sigma^2 = sum_i |r_i|^2 / (3 n - 7) the per-coordinate residual variance of
// the inliers. The INS noise is correlated in time (drift), so this is a
// lower bound; it says when a segment is too short, or its INS too noisy, to
// carry its own scale (the runner then keeps the reference's: withScale()).
//
// A segment with fewer than `min_keyframes` keyframes (inliers), or whose
// keyframes span less time than two INS fix intervals, cannot be fitted
// soundly and is reported as not linked (its frames are then reported lost).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "core/geometry/se3.h"
#include "core/geometry/sim3.h"
#include "core/survey/ins_body_track.h"

namespace hsmap {

// The body track the linker fits segments to (InsBodyTrack(survey,
// kSegmentLinkerInsOptions)): positions only when the INS has no attitude,
// and the attitude slerped between fixes, the arithmetic the linker has
// always used (core/survey/ins_body_track.h, InsAttitudeInterpolation).
inline constexpr InsBodyTrackOptions kSegmentLinkerInsOptions{
    .derive_attitude = false,
    .attitude_interpolation = InsAttitudeInterpolation::quaternion_slerp};

struct SegmentFit {
  bool ok = false;
  std::string failure;
  Sim3 S_W_S;
  int pairs = 0;        // keyframes inside the INS span
  int outliers = 0;     // of them, left out by the RANSAC
  double rms_m = 0.0;   // position residual of the fit over the inliers, metres in W
  double scale_sigma = 0.0;  // 1-sigma of S_W_S.scale() (see the header comment)
  std::string note;     // e.g. why the fit could not be made robust
  // The inlier pairs the fit was made on (p_S, and the INS camera positions p_W_C).
  std::vector<Eigen::Vector3d> p_S, p_W_C;
};

// Fits a segment's keyframe poses T_S_C (at times t) to the INS, the RGB
// camera C at T_B_C in the body B. `outlier_threshold_m`: the RANSAC
// threshold on the camera positions (metres in W).
SegmentFit fitSegmentToIns(const std::vector<double>& times, const std::vector<SE3d>& T_S_C,
                           const InsBodyTrack& ins, const SE3d& T_B_C, int min_keyframes,
                           double outlier_threshold_m = 1.0);

// The fit's rotation with the scale fixed to `scale`, the translation then
// refitted in least squares on the fit's inlier pairs.
Sim3 withScale(const SegmentFit& fit, double scale);

}  // namespace hsmap
