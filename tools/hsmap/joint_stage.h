#pragma once
// The `joint` variant's last stage (docs/JOINT.md). After the sequential
// stages (front-end, geo-referencing, surface, a first cast of the products
// with the survey's guesses), in rounds:
//   1. cross-modal tie points: the RGB ortho-image of the textured mesh and
//      the hyperspectral ortho-image matched (extrinsic_refinement.h,
//      collectTiePointsInRun): UHI pixel (line, sample) <-> mesh point;
//   2. the joint problem (pipelines/joint/joint_problem.h): the trajectory
//      spline, landmarks, INS on the spline, the tie points, T_C_U and d;
//   3. every frame and scan line posed from the spline
//      (T_W_U = T_W_C(t_rec + d) T_C_U), written with calibration.yaml (T_C_U
//      and d with their 1-sigma, the observability warnings);
//   4. the surface rebuilt from the joint keyframe poses and landmarks, and
//      the products cast onto it again;
// until T_C_U and d stop moving or `joint_rounds` are done. Each round is
// reported (tie points, inliers, parameter change). A survey without enough
// confident tie points ends the stage with a warning and the sequential
// result in place.

#include <iosfwd>

#include "core/survey/survey.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/georef/georef_result.h"
#include "tools/hsmap/run_command.h"

namespace hsmap {

void runJointStage(const Survey& survey, const FrontendResult& frontend, const GeorefResult& georef,
                   const RunOptions& options, std::ostream& out);

}  // namespace hsmap
