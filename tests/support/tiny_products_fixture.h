#pragma once
// The `tiny` simulated survey, written once per test program into a temporary
// folder and loaded, with its true scan line poses and true scene: the
// products stage run on the truth should reproduce truth/reflectance's
// footprint and texture (only its values differ: the UHI measures radiance).
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/simulate/simulate_survey.h"

namespace hsmap::testing {

struct TinyProductsSurvey {
  std::filesystem::path folder;
  std::vector<LinePose> true_line_poses;
  std::filesystem::path scene_ply;
  std::filesystem::path truth_reflectance_hdr;
};

inline std::filesystem::path tinyProductsFolder() {
  return std::filesystem::temp_directory_path() / ("hsmap_products_tiny_" + std::to_string(::getpid()));
}

inline const TinyProductsSurvey& tinyProductsSurvey() {
  static const TinyProductsSurvey survey = [] {
    TinyProductsSurvey s;
    s.folder = tinyProductsFolder();
    std::filesystem::remove_all(s.folder);
    std::ostringstream log;
    simulateSurvey(*simulationPreset("tiny"), s.folder, log);
    s.true_line_poses = readLinePoseTable(s.folder / "truth" / "uhi_poses.csv");
    s.scene_ply = s.folder / "truth" / "scene.ply";
    s.truth_reflectance_hdr = s.folder / "truth" / "reflectance.hdr";
    return s;
  }();
  return survey;
}

// Removes the survey when the test program ends.
struct TinyProductsCleanup {
  ~TinyProductsCleanup() {
    std::error_code ignored;
    std::filesystem::remove_all(tinyProductsFolder(), ignored);
  }
};

}  // namespace hsmap::testing

namespace hsmap::testing {
inline const TinyProductsCleanup kTinyProductsCleanup;
}  // namespace hsmap::testing
