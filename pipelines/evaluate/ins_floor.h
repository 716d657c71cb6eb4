#pragma once
// The INS floor: how well the INS alone lets any method place and scale the
// map (a backward-compatible extension of metrics.json, docs/EVALUATE.md).
//
// DATASET.md separates geo-referencing (placement and scale, limited by the
// INS) from shape. A run's rgb_ate_m and rgb_scale_error mix both; the floor
// says how much of them no method could have avoided. Take the TRUE camera
// trajectory, perfect in shape, and geo-reference it as well as the INS
// allows: the similarity S_ins_true (scale s, rotation R, translation t) that
// best maps the true camera trajectory onto the INS fixes, the lever arm to
// the body in metres (turned with the map, not scaled: the INS measures the
// body, the map holds the camera, and the mounting is measured in metres),
//
//   min over (s, R, t) of  sum_k |W_p (p_ins(k) - (s R p_W_C(t_k) + t + R R_W_C(t_k) t_C_B))|^2
//                        + sum_k |W_a log(R_ins(k)^-1 R R_W_C(t_k) R_C_B)|^2   (when ins.csv has attitude)
//
// with T_W_C(t_k) interpolated in SE(3) from truth/rgb_poses.csv at the fix time t_k
// (pose_interpolation.h; fixes outside the frames' time span are skipped: the truth says
// nothing there), T_C_B = T_B_C^-1 from survey.yaml's ins.camera_in_body (exact in
// synthetic surveys), p_ins the fix converted to W (LocalNedFrame at the survey origin) and
// R_ins its roll/pitch/heading. The weights are the survey's stated 1-sigma:
// W_p = diag(1/sigma_horizontal, 1/sigma_horizontal, 1/sigma_depth) (north, east, down),
// W_a = diag(1/sigma_roll, 1/sigma_pitch, 1/sigma_heading) on the body axes x, y, z of the
// attitude error (exact for a level vehicle, where heading turns about z). This is the
// fit georef places the map with (pipelines/georef/ins_similarity.h): a run whose shape
// is exact is at the floor.
// Then
//   ins_floor_rgb_ate_m   = sqrt(mean_i |S p_W_C_true(i) - p_W_C_true(i)|^2) over every frame,
//   ins_floor_scale_error = |s - 1|,
// the rgb_ate_m and rgb_scale_error of a perfect-shape trajectory geo-referenced by the INS.
//
// The fit is the maximum-likelihood similarity of solvers/similarity_fit.h
// (the one georef places the map with), started from the unweighted Umeyama
// alignment (or the identity when the body positions are degenerate for
// it). Without attitude and with collinear fixes (a straight transect) the
// rotation about the line is not observable; it then stays at its start.
//
// The floor is only as good as the fixes' spread: over a path a few INS
// sigmas long the free scale is fitted to noise (docs/EVALUATE.md).
//
// Too few fixes in the frames' span to fix the 7 unknowns (fewer than 3
// without attitude, fewer than 2 with) leave both values missing, with the
// reason.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "core/geometry/sim3.h"
#include "core/survey/ins_fixes_in_world.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey_config.h"
#include "pipelines/evaluate/metric_value.h"

namespace hsmap {



struct InsFloor {
  MetricValue rgb_ate_m;    // ins_floor_rgb_ate_m
  MetricValue scale_error;  // ins_floor_scale_error
  std::size_t fixes_used = 0;
  std::optional<Sim3> S_ins_true;  // the fitted similarity
};

// `frames_true` is T_W_C per frame (strictly increasing t); `ins` gives
// T_B_C and the sigmas (sigma_horizontal_m, sigma_depth_m, sigma_attitude_deg).
InsFloor computeInsFloor(const std::vector<TimedPose>& frames_true,
                         const std::vector<InsFixInWorld>& fixes, const InsConfig& ins);

}  // namespace hsmap
