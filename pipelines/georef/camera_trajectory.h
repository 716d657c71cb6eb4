#pragma once
// CameraTrajectory: the RGB camera's pose T_W_C(t) at any time a product
// needs it (every frame, every scan line at its recorded time + d), from
// the frames posed by vision, bridged by the INS where vision has none.
//
//   vision       t lies between two vision-posed frames at most
//                `max_vision_gap_s` apart: their poses interpolated
//                (interpolatePose: straight line, SO(3) geodesic);
//   ins_bridged  t lies in a longer gap (a tracking loss) or beyond the
//                first/last posed frame, within the INS's span: the INS
//                camera pose T_W_B(t) T_B_C, corrected by the offset between
//                vision and INS at the posed frames next to the gap
//                (position offset in W, rotation offset in C, at each edge,
//                interpolated across the gap), so the bridge meets vision
//                at both ends and follows the vehicle's motion in between;
//   ins_only     no vision at all (the planar variant): T_W_B(t) T_B_C;
//   held         neither vision nor INS reaches t: the nearest pose held.
//                Counted and reported: nothing is extrapolated silently.

#include <vector>

#include "core/geometry/se3.h"
#include "core/survey/ins_body_track.h"

namespace hsmap {

enum class PoseSource { vision, ins_bridged, ins_only, held };
const char* toString(PoseSource source);

struct TimedCameraPose {
  SE3d T_W_C;
  PoseSource source = PoseSource::vision;
};

class CameraTrajectory {
 public:
  // `times`/`T_W_C`: the vision-posed frames (strictly increasing times; may
  // be empty); `ins` may be null (then gaps are held). Throws
  // std::invalid_argument for sizes that differ, times that do not increase,
  // or no vision and no INS.
  CameraTrajectory(std::vector<double> times, std::vector<SE3d> T_W_C, const InsBodyTrack* ins,
                   const SE3d& T_B_C, double max_vision_gap_s);

  TimedCameraPose at(double t) const;
  // True when at(t) comes from vision.
  bool visionCovers(double t) const;

 private:
  // The INS camera pose, or false when the INS does not reach t.
  bool insCamera(double t, SE3d& T_W_C) const;
  // Vision-minus-INS offset at vision frame i: q = q_ins^-1 q_vision, t = t_vision - t_ins (false when the INS does not reach it).
  bool offsetAt(std::size_t i, SE3d& D) const;
  TimedCameraPose heldAt(double t) const;

  std::vector<double> times_;
  std::vector<SE3d> T_W_C_;
  const InsBodyTrack* ins_;
  SE3d T_B_C_;
  double max_vision_gap_s_;
};

}  // namespace hsmap
