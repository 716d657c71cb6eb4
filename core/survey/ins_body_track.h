#pragma once
// InsBodyTrack: the INS fixes in the world frame W, and the body pose
// T_W_B(t) between them, for the stages that look the INS up at a time:
// geo-referencing (pipelines/georef), the joint problem, and the front-end's
// linking of map segments (pipelines/frontend/segment_linker.h).
//
// Each fix (lat, lon, depth) becomes p_W_B through LocalNedFrame at the
// survey's origin (GeographicLib; docs/SURVEY_FORMAT.md). Its attitude is
// the INS's roll, pitch and heading when ins.csv has them. Without them the
// attitude is what a classical mosaic assumes: level (roll = pitch = 0) and
// heading along the track, the direction of travel fitted over a window of
// fixes around t (`heading_window_s`): with decimetre fix noise a heading
// from two consecutive 1 Hz fixes of a vehicle at 0.4 m/s would swing by
// tens of degrees, a straight-line fit over several seconds does not. A
// caller that uses only positions when the INS has no attitude (the segment
// linker) may skip that derivation (derive_attitude = false): q_W_B is then
// the identity, which is no attitude at all; hasAttitude() says so.
//
// Between fixes the position is interpolated on a straight line and the
// attitude along the SO(3) geodesic (core/geometry/pose_interpolation.h), or
// by Eigen's quaternion slerp (InsAttitudeInterpolation below).
// Nothing is extrapolated: covers(t) says whether t lies within the fixes.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "core/geometry/se3.h"

namespace hsmap {

struct Survey;

// A fix in W (core/survey/ins_fixes_in_world.h) with the attitude the
// track uses: measured, or derived (see above).
struct InsBodyFix {
  double t = 0.0;
  Eigen::Vector3d p_W_B = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_W_B = Eigen::Quaterniond::Identity();
  long long line_number = 0;  // line in ins.csv (0 when not read from a file)
};

// How the attitude is interpolated between two fixes. Both are the constant
// rate rotation along the shorter arc and agree to rounding; they differ in
// the last bits. Geo-referencing and the joint problem use the geodesic, the
// segment linker the slerp: each keeps the arithmetic it had when the two had
// INS tracks of their own, so that their results stay bit for bit the same.
enum class InsAttitudeInterpolation {
  so3_geodesic,      // q_a exp(alpha log(q_a^-1 q_b)), interpolatePose(); ends exact
  quaternion_slerp,  // q_a.slerp(alpha, q_b); t at the last fix is alpha = 1 of the last interval
};

struct InsBodyTrackOptions {
  // Without INS attitude: the level, along-track attitude (true), fitted
  // over heading_window_s seconds of fixes; or every q_W_B left at the
  // identity (false), for callers that use only positions then.
  bool derive_attitude = true;
  double heading_window_s = 20.0;
  InsAttitudeInterpolation attitude_interpolation = InsAttitudeInterpolation::so3_geodesic;
};

class InsBodyTrack {
 public:
  // From the survey's INS (survey.ins, survey.origin).
  explicit InsBodyTrack(const Survey& survey, double heading_window_s = 20.0);
  InsBodyTrack(const Survey& survey, const InsBodyTrackOptions& options);
  // From fixes already in W; when !has_attitude their q_W_B are replaced by
  // the level, along-track attitude (unless !options.derive_attitude). Throws
  // std::invalid_argument for no fixes or times that do not increase.
  InsBodyTrack(std::vector<InsBodyFix> fixes, bool has_attitude, double heading_window_s = 20.0);
  InsBodyTrack(std::vector<InsBodyFix> fixes, bool has_attitude,
               const InsBodyTrackOptions& options);

  bool hasAttitude() const { return has_attitude_; }
  const std::vector<InsBodyFix>& fixes() const { return fixes_; }
  bool covers(double t) const;
  double startTime() const { return fixes_.front().t; }
  double endTime() const { return fixes_.back().t; }
  // Median time between consecutive fixes; 0 with one fix.
  double fixInterval() const;

  // T_W_B at t; std::out_of_range when !covers(t).
  SE3d bodyPose(double t) const;

 private:
  void deriveAlongTrackAttitude(double heading_window_s);

  std::vector<InsBodyFix> fixes_;
  std::vector<double> times_;
  bool has_attitude_ = false;
  InsAttitudeInterpolation attitude_interpolation_ = InsAttitudeInterpolation::so3_geodesic;
};

}  // namespace hsmap
