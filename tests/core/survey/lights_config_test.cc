// survey.yaml's optional `lights` block (contract v3): the lamps' positions
// and beam axes in C and the path of their response table.
#include "core/survey/lights_config.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/core/survey/survey_yaml_v3_example.h"

namespace hsmap {
namespace {

using LightsConfigTest = testing::SurveyYamlV3Test;

const std::string kLightsBlock =
    "lights:\n"
    "  response: uhi/lamp_response.csv\n"
    "  lamps:\n"
    "    - position_m: [-0.3, -0.3, 0.0]\n"
    "      axis: [0.0, 0.0, 1.0]\n"
    "    - position_m: [0.3, -0.3, 0.0]\n"
    "      axis: [0.0, 0.0, 1.0]\n";

TEST_F(LightsConfigTest, ReadsTheContractExample) {
  testing::writeText(path_, testing::kSurveyYamlV3);
  const SurveyConfig config = readSurveyConfig(path_);
  ASSERT_TRUE(config.lights.has_value());
  EXPECT_EQ(config.lights->response, "uhi/lamp_response.csv");
  ASSERT_EQ(config.lights->lamps.size(), 2u);
  EXPECT_EQ(config.lights->lamps[0].p_C, Eigen::Vector3d(-0.3, -0.3, 0.0));
  EXPECT_EQ(config.lights->lamps[1].p_C, Eigen::Vector3d(0.3, -0.3, 0.0));
  EXPECT_EQ(config.lights->lamps[0].axis_C, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(config.lights->lamps[1].axis_C, Eigen::Vector3d::UnitZ());
  // The response file's key is remembered, so that loadSurvey reports a
  // missing table at it.
  EXPECT_EQ(config.file_key_lines.at("lights.response"), 30);
}

TEST_F(LightsConfigTest, WithoutLightsThereAreNone) {
  const SurveyConfig config = readVariant(kLightsBlock, "");
  EXPECT_FALSE(config.lights.has_value());
  EXPECT_EQ(config.file_key_lines.count("lights.response"), 0u);
}

TEST_F(LightsConfigTest, NearlyUnitAxisIsNormalised) {
  const SurveyConfig config =
      readVariant("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3",
                  "      axis: [0.0, 0.7071, 0.7071]\n    - position_m: [0.3");
  const Eigen::Vector3d axis = config.lights->lamps[0].axis_C;
  EXPECT_NEAR(axis.norm(), 1.0, 1e-15);
  EXPECT_NEAR(axis.y(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(axis.z(), std::sqrt(0.5), 1e-15);
}

TEST_F(LightsConfigTest, BadAxis) {
  expectError("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3",
              "      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3, -0.3, 0.0]\n      axis: [0, 1, 1]\n"
              "    - position_m: [0.3",
              "line 35, key lights.lamps[1].axis: expected a unit vector [x, y, z] (norm within "
              "0.001 of 1), got norm 1.4142135623730951");
  expectError("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3",
              "      axis: [0, 0, 0]\n    - position_m: [0.3",
              "line 33, key lights.lamps[0].axis: expected a unit vector [x, y, z] (the beam's "
              "axis in C), got the zero vector");
  expectError("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3", "    - position_m: [0.3",
              "line 32, key lights.lamps[0].axis: missing required key");
  expectError("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3",
              "      axis: [0.0, 1.0]\n    - position_m: [0.3",
              "line 33, key lights.lamps[0].axis: expected a list of 3 numbers, got a list of 2");
}

TEST_F(LightsConfigTest, BadPosition) {
  expectError("position_m: [0.3, -0.3, 0.0]", "position_m: [0.3, -0.3, 150]",
              "line 34, key lights.lamps[1].position_m: expected coordinates in [-100, 100] m "
              "(the lamp's centre in C), got 150 at position 3");
}

TEST_F(LightsConfigTest, MissingOrEmptyParts) {
  expectError("  response: uhi/lamp_response.csv\n", "",
              "line 30, key lights.response: missing required key");
  expectError(
      "  lamps:\n    - position_m: [-0.3, -0.3, 0.0]\n      axis: [0.0, 0.0, 1.0]\n"
      "    - position_m: [0.3, -0.3, 0.0]\n      axis: [0.0, 0.0, 1.0]\n",
      "", "line 30, key lights.lamps: missing required key");
  expectError(
      "  lamps:\n    - position_m: [-0.3, -0.3, 0.0]\n      axis: [0.0, 0.0, 1.0]\n"
      "    - position_m: [0.3, -0.3, 0.0]\n      axis: [0.0, 0.0, 1.0]\n",
      "  lamps: []\n",
      "line 31, key lights.lamps: expected a non-empty list of lamps ({position_m, axis}), got an "
      "empty list");
  expectError(kLightsBlock, "lights:\n",
              "line 29, key lights: expected a map with keys (response, lamps), got nothing");
}

TEST_F(LightsConfigTest, UnknownKeys) {
  expectError("  response: uhi/lamp_response.csv\n",
              "  response: uhi/lamp_response.csv\n  beam: gaussian\n",
              "line 31, key lights.beam: unknown key; expected one of: response, lamps");
  expectError("      axis: [0.0, 0.0, 1.0]\n    - position_m: [0.3",
              "      axis: [0.0, 0.0, 1.0]\n      power_w: 50\n    - position_m: [0.3",
              "line 34, key lights.lamps[0].power_w: unknown key; expected one of: position_m, "
              "axis");
}

}  // namespace
}  // namespace hsmap
