#include "core/survey/survey_truth.h"

#include <system_error>

#include "core/survey/survey.h"
#include "core/util/input_error.h"

namespace hsmap {

SurveyTruth loadSurveyTruth(const std::filesystem::path& survey_folder) {
  SurveyTruth truth;
  truth.folder = survey_folder / "truth";
  std::error_code error;
  if (!std::filesystem::is_directory(truth.folder, error)) {
    throw InputError(truth.folder, "",
                     "missing: expected the ground-truth folder truth/ of a simulated survey "
                     "(docs/SURVEY_FORMAT.md)");
  }
  truth.rgb_poses_path = truth.folder / "rgb_poses.csv";
  truth.uhi_poses_path = truth.folder / "uhi_poses.csv";
  truth.calibration_path = truth.folder / "calibration.yaml";
  truth.scene_path = truth.folder / "scene.ply";
  truth.reflectance_header_path = truth.folder / "reflectance.hdr";
  truth.reflectance_data_path = truth.folder / "reflectance.raw";

  for (const std::string& name : expectedTruthFiles()) {
    const std::filesystem::path file = truth.folder / name;
    if (!std::filesystem::is_regular_file(file, error)) {
      throw InputError(file, "",
                       "missing: expected the ground-truth file " + name +
                           " in truth/ (docs/SURVEY_FORMAT.md)");
    }
  }

  truth.rgb_poses = readTruthPoses(truth.rgb_poses_path);
  truth.uhi_poses = readTruthLinePoses(truth.uhi_poses_path);
  truth.calibration = readTruthCalibration(truth.calibration_path);
  return truth;
}

}  // namespace hsmap
