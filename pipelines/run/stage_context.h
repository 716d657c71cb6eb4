#pragma once
// What every stage of a run is given (run_options.h, stage_table.h): the
// survey (loaded once by the runner), the run folder, the variant and where
// to tell the user what happens. A stage reads the files earlier stages left
// in the run folder, never their memory, so any stage can be started on a
// finished run (`--from`) and gives the same files as in a full run.
//
// The stages' own folders in RUN (docs/RUN.md, "The run folder"):
//   frontend/   the visual front-end's map and frames
//   georef/     the geo-referenced trajectory and map (georef_outputs.h)
//   surface/    mesh.ply
//   refine/     uhi_lines.csv, uhi_lines.tum, calibration.yaml, summary.txt
//   joint/      the joint trajectory and map (georef_outputs.h), mesh.ply
//   hyperspectral/, map/rgb_ortho.*   the products
// The contract's trajectory/, calibration.yaml, map/sparse.ply and
// map/mesh.ply are published from them by the runner.

#include <filesystem>
#include <iosfwd>

#include "core/survey/survey.h"
#include "pipelines/run/run_options.h"

namespace hsmap {

namespace stage_folders {
inline constexpr const char* frontend = "frontend";
inline constexpr const char* georef = "georef";
inline constexpr const char* surface = "surface";
inline constexpr const char* refine = "refine";
inline constexpr const char* joint = "joint";
inline constexpr const char* mesh_ply = "mesh.ply";
}  // namespace stage_folders

struct StageContext {
  const Survey& survey;
  std::filesystem::path run;
  Variant variant;
  std::ostream& out;
};

}  // namespace hsmap
