#pragma once
// Every scan line's pose from the camera trajectory, through the extrinsic
// and the time offset: the line recorded at t_rec was exposed at t_rec + d,
//     T_W_U(t_rec + d) = T_W_C(t_rec + d) * T_C_U.

#include <vector>

#include "core/geometry/se3.h"
#include "pipelines/georef/camera_trajectory.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

std::vector<GeorefLinePose> poseScanLines(const std::vector<double>& recorded_times,
                                          const CameraTrajectory& camera, const SE3d& T_C_U,
                                          double time_offset_s);

}  // namespace hsmap
