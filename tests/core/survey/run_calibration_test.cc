#include "core/survey/run_calibration.h"

#include <gtest/gtest.h>

#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

RunCalibration exampleCalibration() {
  RunCalibration calibration;
  calibration.variant = "joint";
  calibration.T_C_U.rotation = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.05).normalized();
  calibration.T_C_U.translation_m = Eigen::Vector3d(0.1, -0.013, 0.0021);
  calibration.sigma_rotation_deg = Eigen::Vector3d(0.05, 0.04, 0.3);
  calibration.sigma_translation_m = Eigen::Vector3d(0.002, 0.0025, 0.01);
  calibration.time_offset_s = 0.0148;
  calibration.time_offset_sigma_s = 0.0004;
  calibration.warnings = {"translation along z: not determined by the survey"};
  return calibration;
}

class RunCalibrationTest : public ::testing::Test {
 protected:
  TempFolder folder_{"run-calibration"};
  std::filesystem::path path_ = folder_ / "calibration.yaml";

  // The example as written, with `from` replaced by `to` (exactly once).
  std::filesystem::path variant(const std::string& from, const std::string& to) {
    writeRunCalibration(path_, exampleCalibration());
    testing::replaceInFile(path_, from, to);
    return path_;
  }
};

TEST_F(RunCalibrationTest, RoundTripsBitExactly) {
  const RunCalibration calibration = exampleCalibration();
  writeRunCalibration(path_, calibration);
  const RunCalibration read = readRunCalibration(path_);
  EXPECT_EQ(read.variant, "joint");
  EXPECT_EQ(read.T_C_U.rotation.coeffs(), calibration.T_C_U.rotation.coeffs());
  EXPECT_EQ(read.T_C_U.translation_m, calibration.T_C_U.translation_m);
  EXPECT_EQ(read.sigma_rotation_deg, calibration.sigma_rotation_deg);
  EXPECT_EQ(read.sigma_translation_m, calibration.sigma_translation_m);
  EXPECT_EQ(read.time_offset_s, calibration.time_offset_s);
  EXPECT_EQ(read.time_offset_sigma_s, calibration.time_offset_sigma_s);
  EXPECT_EQ(read.warnings, calibration.warnings);
  writeRunCalibration(folder_ / "again.yaml", read);
  EXPECT_EQ(TempFolder::read(folder_ / "again.yaml"), TempFolder::read(path_));
}

TEST_F(RunCalibrationTest, TheEstimatedUhiCameraRoundTripsAndIsOptional) {
  RunCalibration calibration = exampleCalibration();
  UhiCameraEstimate camera;
  camera.f = 1514.917;
  camera.cx = 957.31;
  camera.distortion = {0.0213, -0.004};
  camera.sigma.f = 0.83;
  camera.sigma.cx = 0.11;
  camera.sigma.distortion = {0.0007, 0.0};  // k2 held
  calibration.uhi_camera = camera;
  writeRunCalibration(path_, calibration);
  EXPECT_NE(TempFolder::read(path_).find("uhi_camera: {f: 1514.917, cx: 957.31, distortion: [0.0213, -0.004], "
                                         "sigma: {f: 0.83, cx: 0.11, distortion: [7e-04, 0]}}\n"),
            std::string::npos)
      << TempFolder::read(path_);
  const RunCalibration read = readRunCalibration(path_);
  ASSERT_TRUE(read.uhi_camera);
  EXPECT_EQ(read.uhi_camera->f, camera.f);
  EXPECT_EQ(read.uhi_camera->cx, camera.cx);
  EXPECT_EQ(read.uhi_camera->distortion, camera.distortion);
  EXPECT_EQ(read.uhi_camera->sigma.f, camera.sigma.f);
  EXPECT_EQ(read.uhi_camera->sigma.cx, camera.sigma.cx);
  EXPECT_EQ(read.uhi_camera->sigma.distortion, camera.sigma.distortion);
  PushbroomParameters survey_camera;
  survey_camera.samples = 1920;
  const PushbroomParameters applied = read.uhi_camera->appliedTo(survey_camera);
  EXPECT_EQ(applied.samples, 1920);
  EXPECT_EQ(applied.f, camera.f);
  // Without it (not estimated), none is read.
  writeRunCalibration(path_, exampleCalibration());
  EXPECT_FALSE(readRunCalibration(path_).uhi_camera);
  // A bad value is named by its key.
  calibration.uhi_camera->f = 1500.0;
  writeRunCalibration(path_, calibration);
  testing::replaceInFile(path_, "f: 1500,", "f: -3,");
  expectInputError([&] { readRunCalibration(path_); }, path_,
                   "line 11, key uhi_camera.f: expected a number > 0, got -3");
}

TEST_F(RunCalibrationTest, TheEstimatedRgbCameraRoundTripsAndIsOptional) {
  RunCalibration calibration = exampleCalibration();
  RgbCameraEstimate camera;
  camera.fx = 808.125;
  camera.fy = 807.5;
  camera.cx = 483.25;
  camera.cy = 269.75;
  camera.distortion = {-0.021, 0.004, 0.0, 0.0, 0.0};
  camera.sigma.fx = 0.61;
  camera.sigma.fy = 0.6;
  camera.sigma.cx = 0.2;
  camera.sigma.cy = 0.25;
  camera.sigma.distortion = {0.0011, 0.0009, 0.0, 0.0, 0.0};  // p1, p2, k3 held
  calibration.rgb_camera = camera;
  writeRunCalibration(path_, calibration);
  EXPECT_NE(TempFolder::read(path_).find(
                "rgb_camera: {fx: 808.125, fy: 807.5, cx: 483.25, cy: 269.75, distortion: [-0.021, 0.004, 0, 0, 0], "
                "sigma: {fx: 0.61, fy: 0.6, cx: 0.2, cy: 0.25, distortion: [0.0011, 9e-04, 0, 0, 0]}}\n"),
            std::string::npos)
      << TempFolder::read(path_);
  const RunCalibration read = readRunCalibration(path_);
  ASSERT_TRUE(read.rgb_camera);
  EXPECT_EQ(read.rgb_camera->fx, camera.fx);
  EXPECT_EQ(read.rgb_camera->fy, camera.fy);
  EXPECT_EQ(read.rgb_camera->cx, camera.cx);
  EXPECT_EQ(read.rgb_camera->cy, camera.cy);
  EXPECT_EQ(read.rgb_camera->distortion, camera.distortion);
  EXPECT_EQ(read.rgb_camera->sigma.fx, camera.sigma.fx);
  EXPECT_EQ(read.rgb_camera->sigma.cy, camera.sigma.cy);
  EXPECT_EQ(read.rgb_camera->sigma.distortion, camera.sigma.distortion);
  PinholeRadtanParameters survey_camera;
  survey_camera.width = 960;
  survey_camera.height = 540;
  survey_camera.fx = 800.0;
  const PinholeRadtanParameters applied = read.rgb_camera->appliedTo(survey_camera);
  EXPECT_EQ(applied.width, 960);
  EXPECT_EQ(applied.height, 540);
  EXPECT_EQ(applied.fx, camera.fx);
  EXPECT_EQ(applied.distortion, camera.distortion);
  // Without it (not estimated), none is read.
  writeRunCalibration(path_, exampleCalibration());
  EXPECT_FALSE(readRunCalibration(path_).rgb_camera);
  // Bad values are named by their key.
  writeRunCalibration(path_, calibration);
  testing::replaceInFile(path_, "fy: 807.5,", "fy: 0,");
  expectInputError([&] { readRunCalibration(path_); }, path_,
                   "line 11, key rgb_camera.fy: expected a number > 0, got 0");
  writeRunCalibration(path_, calibration);
  testing::replaceInFile(path_, "[-0.021, 0.004, 0, 0, 0], sigma", "[-0.021, 0.004], sigma");
  expectInputError([&] { readRunCalibration(path_); }, path_,
                   "line 11, key rgb_camera.distortion: expected a list of 5 numbers, got a list of 2");
  writeRunCalibration(path_, calibration);
  testing::replaceInFile(path_, "sigma: {fx: 0.61,", "sigma: {fx: -1,");
  expectInputError([&] { readRunCalibration(path_); }, path_,
                   "line 11, key rgb_camera.sigma.fx: expected a number in [0, 1e+06], got -1");
}

TEST_F(RunCalibrationTest, TheWrittenFileLooksAsDocumented) {
  RunCalibration calibration = exampleCalibration();
  calibration.variant = "sequential";
  calibration.T_C_U.rotation = Eigen::Quaterniond::Identity();
  calibration.sigma_translation_m.reset();
  calibration.time_offset_sigma_s.reset();
  calibration.warnings.clear();
  writeRunCalibration(path_, calibration);
  EXPECT_EQ(TempFolder::read(path_),
            "# hsmap run calibration (format: see docs/EVALUATE.md)\n"
            "format: hsmap-calibration/1\n"
            "variant: sequential\n"
            "T_C_U:\n"
            "  rotation_wxyz: [1, 0, 0, 0]\n"
            "  translation_m: [0.1, -0.013, 0.0021]\n"
            "  sigma_rotation_deg: [0.05, 0.04, 0.3]\n"
            "  sigma_translation_m: null\n"
            "time_offset_s: 0.0148\n"
            "time_offset_sigma_s: null\n"
            "warnings: []\n");
  const RunCalibration read = readRunCalibration(path_);
  EXPECT_FALSE(read.sigma_translation_m.has_value());
  EXPECT_FALSE(read.time_offset_sigma_s.has_value());
  EXPECT_TRUE(read.warnings.empty());
}

TEST_F(RunCalibrationTest, ReadsTheContractExample) {
  writeText(path_,
            "format: hsmap-calibration/1\n"
            "variant: joint\n"
            "T_C_U:\n"
            "  rotation_wxyz: [1, 0, 0, 0]\n"
            "  translation_m: [0.1, 0, 0]\n"
            "  sigma_rotation_deg: [0.1, 0.1, 0.2]   # about U's axes\n"
            "  sigma_translation_m: [0.01, 0.01, 0.02]\n"
            "time_offset_s: 0.0148\n"
            "time_offset_sigma_s: 0.0004\n"
            "warnings: [\"z not determined\"]\n");
  const RunCalibration read = readRunCalibration(path_);
  EXPECT_EQ(read.sigma_rotation_deg, Eigen::Vector3d(0.1, 0.1, 0.2));
  EXPECT_EQ(read.time_offset_sigma_s, 0.0004);
  EXPECT_EQ(read.warnings, std::vector<std::string>{"z not determined"});
}

TEST_F(RunCalibrationTest, BadInputsAreNamedByLineAndKey) {
  expectInputError([&] { readRunCalibration(variant("variant: joint", "variant: best")); }, path_,
                   "line 3, key variant: unknown variant 'best'; expected one of: stacked, "
                   "planar, sequential, joint");
  expectInputError(
      [&] {
        readRunCalibration(variant("sigma_translation_m: [0.002, 0.0025, 0.01]",
                                   "sigma_translation_m: abc"));
      },
      path_,
      "line 8, key T_C_U.sigma_translation_m: expected a list of 3 numbers >= 0 or null (not "
      "estimated), got 'abc'");
  expectInputError(
      [&] {
        readRunCalibration(variant("sigma_rotation_deg: [0.05, 0.04, 0.3]",
                                   "sigma_rotation_deg: [0.05, -0.04, 0.3]"));
      },
      path_, "line 7, key T_C_U.sigma_rotation_deg[1]: expected a number >= 0, got -0.04");
  expectInputError(
      [&] { readRunCalibration(variant("time_offset_sigma_s: 4e-04\n", "")); }, path_,
      "line 2, key time_offset_sigma_s: missing required key");
  expectInputError(
      [&] { readRunCalibration(variant("time_offset_s: 0.0148", "time_offset_s: 1e5")); }, path_,
      "line 9, key time_offset_s: expected a number in [-3600, 3600], got 1e+05");
  expectInputError(
      [&] { readRunCalibration(variant("format: hsmap-calibration/1", "format: hsmap-truth/1")); },
      path_, "line 2, key format: unsupported format 'hsmap-truth/1'; expected "
             "'hsmap-calibration/1'");
}

TEST_F(RunCalibrationTest, WriterRefusesWhatTheReaderWouldRefuse) {
  RunCalibration calibration = exampleCalibration();
  calibration.variant = "";
  try {
    writeRunCalibration(path_, calibration);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "writeRunCalibration: invalid calibration: " + path_.string() +
                  ":line 3, key variant: expected a non-empty text value, got ''");
  }
  calibration = exampleCalibration();
  calibration.time_offset_sigma_s = -1.0;
  EXPECT_THROW(writeRunCalibration(path_, calibration), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path_));
}

}  // namespace
}  // namespace hsmap
