#pragma once
// The refine stage (sequential): the reference paper's refinement of the
// RGB-UHI extrinsic T_C_U from the RGB and hyperspectral ortho-images
// (pipelines/calibration/extrinsic_refinement.h), `rounds` times: cast the
// scan lines onto the mesh (into a scratch folder), match the two
// ortho-images, refine T_C_U, re-pose the lines.
//
//   reads   RUN/georef/uhi_lines.csv, calibration.yaml, map_placement.yaml
//           (T_C_U's translation 1-sigma carries the map's scale uncertainty);
//           RUN/surface/mesh.ply
//   writes  RUN/refine/uhi_lines.csv, uhi_lines.tum, calibration.yaml, summary.txt
//
// With 0 rounds, or when no round refines, the georef stage's lines and
// calibration are written unchanged (with the reason among the warnings).

#include "pipelines/run/stage_context.h"

namespace hsmap {

void runRefineStage(const StageContext& context, const RefineStageOptions& options);

}  // namespace hsmap
