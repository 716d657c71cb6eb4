#pragma once
// The joint stage (docs/JOINT.md): from the sequential start (RUN/frontend/,
// RUN/georef/, RUN/surface/mesh.ply), in rounds:
//   1. cross-modal tie points: in the first round (and every round with
//      `tie_points = ortho`) the scan lines are cast onto the mesh into a
//      scratch folder and the two ortho-images matched; later rounds match
//      each push-broom strip against its prediction from the RGB frames;
//   2. the joint problem (pipelines/joint/joint_problem.h): the trajectory
//      spline, landmarks, INS on the spline, the tie points, T_C_U and d;
//   3. every frame and scan line posed from the spline
//      (T_W_U = T_W_C(t_rec + d) T_C_U);
//   4. the surface meshed again from the joint keyframe poses and landmarks
//      (surface_meshing.h), for the next round and the products;
// until T_C_U, d and the trajectory stop moving or `rounds` are done.
//
//   writes  RUN/joint/ (georef_outputs.h: the trajectory, calibration.yaml
//           with T_C_U and d and their 1-sigma, the map) and RUN/joint/mesh.ply
//
// A survey without enough confident tie points ends the stage with a warning
// and the sequential result in RUN/joint/.

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runJointStage(const StageContext& context, const JointStageOptions& options,
                   SurfaceStageOptions surface);

}  // namespace hsmap
