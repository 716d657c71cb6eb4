#pragma once
// SurveyTruth: the ground truth of a simulated survey (docs/SURVEY_FORMAT.md,
// "truth/"), as `hsmap evaluate` and the tests compare results against it.
//
// loadSurveyTruth(survey_folder) first checks that every file of truth/
// exists (in the order of expectedTruthFiles(): rgb_poses.csv,
// uhi_poses.csv, calibration.yaml, scene.ply, reflectance.hdr,
// reflectance.raw), so that a half-copied truth folder is reported by the
// name of the first missing file, then reads the three text files strictly
// (truth_files.h). The mesh and the reflectance raster can be large and are
// only needed by some metrics: their paths are returned, not their contents.
// Cross-checks against the survey (pose counts against frames.csv and
// lines.csv, attenuation count against the cube's bands) need the loaded
// survey and belong to the caller.
//
// Errors are InputError naming the file, e.g.
//   "survey/truth/scene.ply: missing: expected the ground-truth file scene.ply in truth/ ..."

#include <filesystem>
#include <vector>

#include "core/survey/truth_files.h"

namespace hsmap {

struct SurveyTruth {
  std::filesystem::path folder;                   // <survey>/truth
  std::filesystem::path rgb_poses_path;           // truth/rgb_poses.csv
  std::filesystem::path uhi_poses_path;           // truth/uhi_poses.csv
  std::filesystem::path calibration_path;         // truth/calibration.yaml
  std::filesystem::path scene_path;               // truth/scene.ply (binary PLY, triangles in W)
  std::filesystem::path reflectance_header_path;  // truth/reflectance.hdr (ENVI float32)
  std::filesystem::path reflectance_data_path;    // truth/reflectance.raw

  std::vector<TruthPose> rgb_poses;      // T_W_C per RGB frame
  std::vector<TruthLinePose> uhi_poses;  // T_W_U per scan line at its true time
  TruthCalibration calibration;
};

// Throws InputError when truth/ or one of its files is missing or a text file
// is malformed.
SurveyTruth loadSurveyTruth(const std::filesystem::path& survey_folder);

}  // namespace hsmap
