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
// INS camera positions (InsCameraTrack). Each fix is converted to local NED
// W (core/geometry/local_ned_frame.h, at the survey's origin), the body
// position and attitude are interpolated at the keyframe time (linear /
// slerp between the 1 Hz fixes), and the lever arm is added:
//     p_W_C = p_W_B + R_W_B t_B_C           (T_B_C = survey.config.ins.T_B_C).
// When the INS has no attitude, R_W_B is taken from the fit itself:
// R_W_B = R_W_C R_B_C^T with R_W_C = R_W_S R_S_C, the fit repeated twice.
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

namespace hsmap {

struct Survey;

class InsCameraTrack {
 public:
  // From the survey's INS (survey.ins, survey.origin, survey.config.ins.T_B_C).
  explicit InsCameraTrack(const Survey& survey);
  // From body poses already in W (tests).
  InsCameraTrack(std::vector<double> times, std::vector<Eigen::Vector3d> p_W_B,
                 std::vector<Eigen::Quaterniond> q_W_B, bool has_attitude, const SE3d& T_B_C);

  bool hasAttitude() const { return has_attitude_; }
  bool covers(double t) const;
  double fixInterval() const;  // median time between fixes
  const SE3d& T_B_C() const { return T_B_C_; }
  // Body position and attitude at t (t inside the fixes' span).
  Eigen::Vector3d bodyPosition(double t) const;
  Eigen::Quaterniond bodyAttitude(double t) const;

 private:
  std::size_t segmentIndex(double t, double* alpha) const;
  std::vector<double> times_;
  std::vector<Eigen::Vector3d> p_W_B_;
  std::vector<Eigen::Quaterniond> q_W_B_;
  bool has_attitude_ = false;
  SE3d T_B_C_;
};

struct SegmentFit {
  bool ok = false;
  std::string failure;
  Sim3 S_W_S;
  int pairs = 0;
  double rms_m = 0.0;  // position residual of the fit, metres in W
};

// Fits a segment's keyframe poses T_S_C (at times t) to the INS.
SegmentFit fitSegmentToIns(const std::vector<double>& times, const std::vector<SE3d>& T_S_C,
                           const InsCameraTrack& ins, int min_keyframes);

}  // namespace hsmap
