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
// A segment with fewer than `min_keyframes` keyframes, or whose keyframes
// span less time than two INS fix intervals, cannot be fitted soundly and is
// reported as not linked (its frames are then reported lost).

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
  int pairs = 0;
  double rms_m = 0.0;  // position residual of the fit, metres in W
};

// Fits a segment's keyframe poses T_S_C (at times t) to the INS, the RGB
// camera C at T_B_C in the body B.
SegmentFit fitSegmentToIns(const std::vector<double>& times, const std::vector<SE3d>& T_S_C,
                           const InsBodyTrack& ins, const SE3d& T_B_C, int min_keyframes);

}  // namespace hsmap
