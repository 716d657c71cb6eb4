// loadSurvey and `hsmap inspect`'s summary on a contract-v3 survey: the
// DATASET.md example survey.yaml (camera_sigma for both cameras, two lamps)
// over the built-in sample survey's files, with a uhi/lamp_response.csv.
#include <gtest/gtest.h>

#include <sstream>

#include "core/survey/lamp_response_csv.h"
#include "core/survey/survey.h"
#include "core/survey/survey_summary.h"
#include "pipelines/sample_survey.h"
#include "tests/core/survey/survey_yaml_v3_example.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::readText;
using testing::replaceInFile;
using testing::writeText;

// The sample's own camera sizes in the contract's example.
std::string v3SurveyYamlForTheSample() {
  std::string text = testing::surveyYamlV3With("width: 960, height: 540", "width: 160, height: 120");
  const auto at = text.find("samples: 1920");
  return text.replace(at, 13, "samples: 64");
}

const std::string kRgbGeorefWarning =
    "survey.yaml gives rgb.camera_sigma (self-calibrated intrinsics): the sequential and joint "
    "variants estimate them in the geo-referencing bundle adjustment; planar and stacked use rgb.camera "
    "as given";
const std::string kUhiJointWarning =
    "survey.yaml gives uhi.camera_sigma (self-calibrated intrinsics): the joint variant estimates "
    "them; the other variants use uhi.camera as given";

class SurveyV3LoadTest : public ::testing::Test {
 protected:
  testing::TempFolder temp_{"survey-v3"};
  std::filesystem::path survey_ = temp_ / "sample";
  std::filesystem::path yaml_ = survey_ / "survey.yaml";
  std::filesystem::path response_ = survey_ / "uhi/lamp_response.csv";

  void SetUp() override {
    writeSampleSurvey(survey_);
    writeText(yaml_, v3SurveyYamlForTheSample());
    std::vector<double> dn;
    for (int band = 0; band < 16; ++band) dn.push_back(1200.0 + 100.0 * band);  // 1200 .. 2700
    writeLampResponseCsv(response_, dn);
  }
};

TEST_F(SurveyV3LoadTest, TheContractExampleLoads) {
  const Survey survey = loadSurvey(survey_);
  ASSERT_TRUE(survey.config.lights.has_value());
  EXPECT_EQ(survey.config.lights->lamps.size(), 2u);
  EXPECT_EQ(survey.lamp_response_path, response_);
  ASSERT_EQ(survey.lamp_response_dn.size(), 16u);
  EXPECT_EQ(survey.lamp_response_dn.front(), 1200.0);
  EXPECT_EQ(survey.lamp_response_dn.back(), 2700.0);
  ASSERT_TRUE(survey.config.rgb.camera_sigma.has_value());
  ASSERT_TRUE(survey.config.uhi.camera_sigma.has_value());
  EXPECT_EQ(survey.warnings, (std::vector<std::string>{kRgbGeorefWarning, kUhiJointWarning}));
}

TEST_F(SurveyV3LoadTest, TheWarningNamesOnlyTheCamerasWhoseSigmaAsksForCalibration) {
  replaceInFile(yaml_,
                "  camera_sigma: {fx: 8, fy: 8, cx: 4, cy: 4, distortion: [0.02, 0.02, 0.001, "
                "0.001, 0.02]}\n",
                "  camera_sigma: {fx: 0}\n");
  EXPECT_EQ(loadSurvey(survey_).warnings, (std::vector<std::string>{kUhiJointWarning}));
  replaceInFile(yaml_, "  camera_sigma: {f: 15, cx: 3, distortion: [0.02, 0.01]}\n", "");
  EXPECT_TRUE(loadSurvey(survey_).warnings.empty());
}

TEST_F(SurveyV3LoadTest, WithoutLightsTheResponseIsNotRead) {
  SurveyConfig config = readSurveyConfig(yaml_);
  config.lights.reset();
  writeSurveyConfig(yaml_, config);
  std::filesystem::remove(response_);
  const Survey survey = loadSurvey(survey_);
  EXPECT_TRUE(survey.lamp_response_path.empty());
  EXPECT_TRUE(survey.lamp_response_dn.empty());
}

TEST_F(SurveyV3LoadTest, MissingResponseIsReportedAtItsKey) {
  std::filesystem::remove(response_);
  expectInputError([&] { loadSurvey(survey_); }, yaml_,
                   "line 30, key lights.response: the file '" + response_.string() +
                       "' not found; expected the lamp response table (band,dn)");
}

TEST_F(SurveyV3LoadTest, ResponseWithTooFewOrTooManyBands) {
  const std::string cube = (survey_ / "uhi/cube.hdr").string();
  writeLampResponseCsv(response_, std::vector<double>(15, 1000.0));
  expectInputError([&] { loadSurvey(survey_); }, response_,
                   "line 16: the table ends at band 14 (15 rows), but the cube " + cube +
                       " has 16 bands; expected one row per UHI band");
  writeLampResponseCsv(response_, std::vector<double>(17, 1000.0));
  expectInputError([&] { loadSurvey(survey_); }, response_,
                   "line 18: row for band 16, but the cube " + cube +
                       " has 16 bands; expected one row per UHI band (17 rows given)");
}

TEST_F(SurveyV3LoadTest, BadResponseRowsNameTheFileAndLine) {
  replaceInFile(response_, "\n3,1500\n", "\n3,0\n");
  expectInputError([&] { loadSurvey(survey_); }, response_,
                   "line 5: column 'dn': expected a DN > 0 (one lamp's response on a white "
                   "target at 1 m), got 0");
  replaceInFile(response_, "\n3,0\n", "\n2,1500\n");
  expectInputError([&] { loadSurvey(survey_); }, response_,
                   "line 5: column 'band': expected band 3 (one row per UHI band, counting from 0 "
                   "in order), got 2");
}

TEST_F(SurveyV3LoadTest, InspectPrintsTheSigmasTheLightsAndTheWarning) {
  std::ostringstream text;
  printSurveySummary(text, summarizeSurvey(loadSurvey(survey_)));
  const std::string printed = text.str();
  for (const std::string& expected :
       {std::string("; image list ") + (survey_ / "rgb/frames.csv").string() +
            "\n       camera_sigma: fx 8.00, fy 8.00, cx 4.00, cy 4.00, distortion [0.02, 0.02, "
            "0.001, 0.001, 0.02] (intrinsics estimated by the geo-referencing bundle adjustment)\n  UHI: ",
        std::string(" s\n       camera_sigma: f 15.00, cx 3.00, distortion [0.02, 0.01] "
                    "(intrinsics estimated by the joint variant)\n  INS: "),
        "  INS: position and attitude\n  lights: 2 lamps; response " + response_.string() +
            ": 16 bands, DN 1200.0 - 2700.0\n"
            "    lamp 0: position [-0.300, -0.300, 0.000] m, axis [0.000, 0.000, 1.000] (in C)\n"
            "    lamp 1: position [0.300, -0.300, 0.000] m, axis [0.000, 0.000, 1.000] (in C)\n"
            "streams:\n",
        "warnings:\n  - " + kRgbGeorefWarning + "\n  - " + kUhiJointWarning + "\n"}) {
    EXPECT_NE(printed.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                         << printed;
  }
}

// A survey without the v3 keys prints exactly as before: no sigma or lights line.
TEST_F(SurveyV3LoadTest, InspectOfASurveyWithoutThemHasNoSuchLines) {
  testing::TempFolder plain("survey-v2");
  writeSampleSurvey(plain / "sample");
  std::ostringstream text;
  printSurveySummary(text, summarizeSurvey(loadSurvey(plain / "sample")));
  EXPECT_EQ(text.str().find("camera_sigma"), std::string::npos) << text.str();
  EXPECT_EQ(text.str().find("lights"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("warnings: none\n"), std::string::npos) << text.str();
}

}  // namespace
}  // namespace hsmap
