#include "pipelines/georef/planar_georef.h"

#include "core/survey/ins_body_track.h"
#include "pipelines/georef/camera_trajectory.h"
#include "pipelines/georef/scan_line_poses.h"

namespace hsmap {

GeorefResult runPlanarGeoref(const Survey& survey, const GeorefOptions& options) {
  options.validate();
  GeorefResult result;
  result.variant = "planar";
  const InsBodyTrack ins(survey, options.heading_window_s);
  const SE3d T_B_C(survey.config.ins.T_B_C.rotation, survey.config.ins.T_B_C.translation_m);
  const CameraTrajectory camera({}, {}, &ins, T_B_C, options.max_vision_gap_s);
  const std::vector<double>& times = survey.rgb.times();
  for (std::size_t i = 0; i < times.size(); ++i) {
    const TimedCameraPose pose = camera.at(times[i]);
    result.frames.push_back({int(i), times[i], pose.T_W_C, pose.source});
  }
  result.T_C_U = SE3d(survey.config.uhi.T_C_U.rotation, survey.config.uhi.T_C_U.translation_m);
  result.time_offset_s = survey.config.uhi.time_offset_s;
  result.lines = poseScanLines(survey.line_times, camera, result.T_C_U, result.time_offset_s);
  if (!ins.hasAttitude()) {
    result.warnings.push_back(
        "the INS has no attitude: the planar trajectory assumes a level vehicle heading along "
        "its track (fitted over " + std::to_string(int(options.heading_window_s)) + " s of fixes)");
  }
  return result;
}

}  // namespace hsmap
