#pragma once
// `hsmap evaluate RUN --truth SURVEY/truth`: a run's results against the
// survey's ground truth (docs/EVALUATE.md).
//
// evaluateRun() computes every metric of metrics.json from inputs already
// loaded and checked (evaluation_inputs.h): the view distance of the frames'
// view Sim(3) (view_distance.h, rays on truth/scene.ply), trajectory metrics
// (trajectory_metrics.h), calibration errors (calibration_metrics.h), the
// mesh metrics when the run has RUN/map/mesh.ply (mesh_metrics.h, with the
// frames' view Sim(3) and, as extensions, with the positions-only and the
// attitude-anchored alignments), the ortho-image metrics when the run has
// RUN/hyperspectral/ortho.hdr (ortho_metrics.h, against
// truth/reflectance.hdr, in the UTM zone of the survey origin) and, with its
// ancillary layer, the pixel error (ortho_pixel_error.h: the true line
// poses, the true UHI camera and rays on truth/scene.ply). Then timings and
// peak memory from run.yaml and the INS floor (ins_floor.h).
//
// evaluateRunFolder() is the whole command: load, compute, write
// RUN/metrics.json atomically, and the ortho-image's matched patches to
// RUN/report/ortho_patches.csv. It throws InputError for bad input.

#include <filesystem>

#include "pipelines/evaluate/evaluation_inputs.h"
#include "pipelines/evaluate/evaluation_metrics.h"

namespace hsmap {

// Why every metric of a `stacked` run is null.
inline constexpr const char* kStackedHasNoPoses =
    "the stacked variant poses nothing: scan lines side by side, no map position";
// Why its RGB intrinsics' errors are null.
inline constexpr const char* kStackedUsesNoRgbCamera = "the stacked variant uses no RGB camera";
inline constexpr const char* kStackedMakesNoReflectance =
    "the stacked variant makes no reflectance product: its scan lines have no surface to place the lamps on";

EvaluationMetrics evaluateRun(const EvaluationInputs& inputs);

struct EvaluationReport {
  EvaluationMetrics metrics;
  std::filesystem::path metrics_path;  // RUN/metrics.json, written
  // RUN/report/ortho_patches.csv (each matched patch's centre in W, its
  // displacement and response), written when the ortho-image was measured.
  std::filesystem::path ortho_patches_path;
  std::vector<std::string> warnings;   // from loading (evaluation_inputs.h)
};

EvaluationReport evaluateRunFolder(const std::filesystem::path& run_folder,
                                   const std::filesystem::path& truth_folder);

}  // namespace hsmap
