// survey.yaml's rgb.camera_sigma and uhi.camera_sigma (contract v3): read,
// validated and written back; every key optional, absent = 0 = held fixed.
#include "core/survey/camera_sigma.h"

#include <gtest/gtest.h>

#include "tests/core/survey/survey_yaml_v3_example.h"

namespace hsmap {
namespace {

using CameraSigmaTest = testing::SurveyYamlV3Test;

const std::string kRgbSigma =
    "  camera_sigma: {fx: 8, fy: 8, cx: 4, cy: 4, distortion: [0.02, 0.02, 0.001, 0.001, 0.02]}";
const std::string kUhiSigma = "  camera_sigma: {f: 15, cx: 3, distortion: [0.02, 0.01]}";

TEST_F(CameraSigmaTest, ReadsTheContractExample) {
  testing::writeText(path_, testing::kSurveyYamlV3);
  const SurveyConfig config = readSurveyConfig(path_);
  ASSERT_TRUE(config.rgb.camera_sigma.has_value());
  EXPECT_EQ(config.rgb.camera_sigma->fx, 8.0);
  EXPECT_EQ(config.rgb.camera_sigma->fy, 8.0);
  EXPECT_EQ(config.rgb.camera_sigma->cx, 4.0);
  EXPECT_EQ(config.rgb.camera_sigma->cy, 4.0);
  EXPECT_EQ(config.rgb.camera_sigma->distortion,
            (std::array<double, 5>{0.02, 0.02, 0.001, 0.001, 0.02}));
  ASSERT_TRUE(config.uhi.camera_sigma.has_value());
  EXPECT_EQ(config.uhi.camera_sigma->f, 15.0);
  EXPECT_EQ(config.uhi.camera_sigma->cx, 3.0);
  EXPECT_EQ(config.uhi.camera_sigma->distortion, (std::array<double, 2>{0.02, 0.01}));
  EXPECT_TRUE(config.rgb.camera_sigma->asksForCalibration());
  EXPECT_TRUE(config.uhi.camera_sigma->asksForCalibration());
}

TEST_F(CameraSigmaTest, AbsentKeysAreZeroAndAbsentMapsAreNone) {
  SurveyConfig config = readVariant(kUhiSigma, "  camera_sigma: {cx: 3}");
  ASSERT_TRUE(config.uhi.camera_sigma.has_value());
  EXPECT_EQ(config.uhi.camera_sigma->f, 0.0);
  EXPECT_EQ(config.uhi.camera_sigma->cx, 3.0);
  EXPECT_EQ(config.uhi.camera_sigma->distortion, (std::array<double, 2>{0, 0}));

  config = readVariant(kRgbSigma, "  camera_sigma: {}");
  ASSERT_TRUE(config.rgb.camera_sigma.has_value());
  EXPECT_FALSE(config.rgb.camera_sigma->asksForCalibration());  // all zeros: everything fixed

  config = readVariant(kRgbSigma + "\n", "");
  EXPECT_FALSE(config.rgb.camera_sigma.has_value());
}

TEST_F(CameraSigmaTest, UnknownKeys) {
  expectError(kUhiSigma, "  camera_sigma: {f: 15, k1: 0.1}",
              "line 12, key uhi.camera_sigma.k1: unknown key; expected one of: f, cx, distortion");
  expectError(kRgbSigma, "  camera_sigma: {fx: 8, f: 8}",
              "line 7, key rgb.camera_sigma.f: unknown key; expected one of: fx, fy, cx, cy, "
              "distortion");
}

TEST_F(CameraSigmaTest, WrongDistortionLength) {
  expectError("distortion: [0.02, 0.01]", "distortion: [0.02, 0.01, 0.0]",
              "line 12, key uhi.camera_sigma.distortion: expected a list of 2 numbers, got a list "
              "of 3");
  expectError("distortion: [0.02, 0.02, 0.001, 0.001, 0.02]", "distortion: [0.02, 0.02]",
              "line 7, key rgb.camera_sigma.distortion: expected a list of 5 numbers, got a list "
              "of 2");
}

TEST_F(CameraSigmaTest, ValuesOutOfRange) {
  expectError("{f: 15,", "{f: -1,",
              "line 12, key uhi.camera_sigma.f: expected a number in [0, 1e+06], got -1");
  expectError("{fx: 8, fy: 8, cx: 4", "{fx: 8, fy: 2e6, cx: 4",
              "line 7, key rgb.camera_sigma.fy: expected a number in [0, 1e+06], got 2e+06");
  expectError("{f: 15,", "{f: nan,",
              "line 12, key uhi.camera_sigma.f: expected a finite number, got 'nan'");
  expectError("distortion: [0.02, 0.01]", "distortion: [0.02, -0.01]",
              "line 12, key uhi.camera_sigma.distortion: expected 2 sigmas in [0, 1000], got -0.01 "
              "at position 2");
  expectError("distortion: [0.02, 0.02, 0.001, 0.001, 0.02]",
              "distortion: [0.02, 0.02, 0.001, 0.001, 1001]",
              "line 7, key rgb.camera_sigma.distortion: expected 5 sigmas in [0, 1000], got 1001 "
              "at position 5");
  expectError(kUhiSigma, "  camera_sigma: 15",
              "line 12, key uhi.camera_sigma: expected a map with keys (f, cx, distortion), got "
              "'15'");
}

}  // namespace
}  // namespace hsmap
