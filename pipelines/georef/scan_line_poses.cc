#include "pipelines/georef/scan_line_poses.h"

namespace hsmap {

std::vector<GeorefLinePose> poseScanLines(const std::vector<double>& recorded_times,
                                          const CameraTrajectory& camera, const SE3d& T_C_U,
                                          double time_offset_s) {
  std::vector<GeorefLinePose> lines(recorded_times.size());
  for (std::size_t i = 0; i < recorded_times.size(); ++i) {
    const double t = recorded_times[i] + time_offset_s;
    const TimedCameraPose pose = camera.at(t);
    lines[i] = {static_cast<long long>(i), t, pose.T_W_C * T_C_U, pose.source};
  }
  return lines;
}

}  // namespace hsmap
