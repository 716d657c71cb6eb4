#include "core/survey/survey_truth.h"

#include <gtest/gtest.h>

#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;
using testing::writeText;

std::string inputErrorMessage(const std::filesystem::path& survey) {
  try {
    loadSurveyTruth(survey);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

class SurveyTruthTest : public ::testing::Test {
 protected:
  SurveyTruthTest() {
    std::filesystem::create_directories(truth_);
    writeTruthPoses(truth_ / "rgb_poses.csv",
                    {{10.0, SE3d(Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5), Eigen::Vector3d(1, 2, 3))},
                     {10.04, SE3d()}});
    writeTruthLinePoses(truth_ / "uhi_poses.csv",
                        {{0, 10.015, SE3d()},
                         {1, 10.025, SE3d(Eigen::Quaterniond(0, 1, 0, 0), Eigen::Vector3d(0, 0, 9))}});
    TruthCalibration calibration;
    calibration.time_offset_s = 0.015;
    calibration.rgb_camera = {960, 540, 800, 800, 480, 270, {0, 0, 0, 0, 0}};
    calibration.uhi_camera = {1920, 1500, 960, {0, 0}};
    calibration.water_attenuation_per_m = {0.1, 0.2, 0.3};
    writeTruthCalibration(truth_ / "calibration.yaml", calibration);
    // Content does not matter: loadSurveyTruth only checks that they exist.
    writeText(truth_ / "scene.ply", "ply\n");
    writeText(truth_ / "reflectance.hdr", "ENVI\n");
    writeText(truth_ / "reflectance.raw", "");
  }

  TempFolder folder_{"survey-truth"};
  std::filesystem::path truth_ = folder_ / "truth";
};

TEST_F(SurveyTruthTest, LoadsTheTextFilesAndNamesTheOthers) {
  const SurveyTruth truth = loadSurveyTruth(folder_.path());
  EXPECT_EQ(truth.folder, truth_);
  EXPECT_EQ(truth.rgb_poses_path, truth_ / "rgb_poses.csv");
  EXPECT_EQ(truth.uhi_poses_path, truth_ / "uhi_poses.csv");
  EXPECT_EQ(truth.calibration_path, truth_ / "calibration.yaml");
  EXPECT_EQ(truth.scene_path, truth_ / "scene.ply");
  EXPECT_EQ(truth.reflectance_header_path, truth_ / "reflectance.hdr");
  EXPECT_EQ(truth.reflectance_data_path, truth_ / "reflectance.raw");
  ASSERT_EQ(truth.rgb_poses.size(), 2u);
  EXPECT_EQ(truth.rgb_poses[1].t, 10.04);
  EXPECT_EQ(truth.rgb_poses[0].T_W_X.t, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(truth.rgb_poses[0].T_W_X.q.coeffs(), Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5).coeffs());
  ASSERT_EQ(truth.uhi_poses.size(), 2u);
  EXPECT_EQ(truth.uhi_poses[1].line, 1);
  EXPECT_EQ(truth.uhi_poses[1].t, 10.025);
  EXPECT_EQ(truth.uhi_poses[1].T_W_U.q.x(), 1.0);
  EXPECT_EQ(truth.calibration.time_offset_s, 0.015);
  EXPECT_EQ(truth.calibration.water_attenuation_per_m, (std::vector<double>{0.1, 0.2, 0.3}));
}

TEST_F(SurveyTruthTest, NoTruthFolder) {
  std::filesystem::remove_all(truth_);
  EXPECT_EQ(inputErrorMessage(folder_.path()),
            truth_.string() +
                ": missing: expected the ground-truth folder truth/ of a simulated survey "
                "(docs/SURVEY_FORMAT.md)");
}

TEST_F(SurveyTruthTest, EachMissingFileIsNamed) {
  ASSERT_EQ(expectedTruthFiles().size(), 6u);
  for (const std::string& name : expectedTruthFiles()) {
    const std::filesystem::path file = truth_ / name;
    const std::filesystem::path aside = folder_ / (name + ".aside");
    std::filesystem::rename(file, aside);
    EXPECT_EQ(inputErrorMessage(folder_.path()),
              file.string() + ": missing: expected the ground-truth file " + name +
                  " in truth/ (docs/SURVEY_FORMAT.md)");
    std::filesystem::rename(aside, file);
  }
  EXPECT_NO_THROW(loadSurveyTruth(folder_.path()));
}

TEST_F(SurveyTruthTest, MalformedTextFilesReportTheirOwnErrors) {
  testing::replaceInFile(truth_ / "uhi_poses.csv", "1,10.025,", "1,10.01,");
  EXPECT_EQ(inputErrorMessage(folder_.path()),
            (truth_ / "uhi_poses.csv").string() +
                ":line 3: time 't' = 10.01 is earlier than the previous row's 10.015: rows must "
                "be in time order");
}

}  // namespace
}  // namespace hsmap
