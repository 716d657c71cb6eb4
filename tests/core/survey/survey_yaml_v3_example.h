#pragma once
// The v3 survey.yaml of the data contract (/work/shared/DATASET.md's example,
// with numbers for its symbolic distortion): docs/SURVEY_FORMAT.md's example
// plus camera_sigma for both cameras and a lights block, with the line
// numbers that the expected messages use. Shared by the tests of the v3 keys.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/survey/survey_config.h"
#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap::testing {

// clang-format off
inline const char* const kSurveyYamlV3 =
    "format: hsmap-survey/1\n"                                                     // 1
    "name: rugged-demo\n"                                                          // 2
    "rgb:\n"                                                                       // 3
    "  frames: rgb/frames.csv\n"                                                   // 4
    "  camera: {model: pinhole-radtan, width: 960, height: 540,\n"                 // 5
    "           fx: 800, fy: 800, cx: 480, cy: 270, distortion: [0, 0, 0, 0, 0]}\n"  // 6
    "  camera_sigma: {fx: 8, fy: 8, cx: 4, cy: 4,"
    " distortion: [0.02, 0.02, 0.001, 0.001, 0.02]}\n"                             // 7
    "uhi:\n"                                                                       // 8
    "  cube: uhi/cube.hdr\n"                                                       // 9
    "  lines: uhi/lines.csv\n"                                                     // 10
    "  camera: {model: pushbroom, samples: 1920, f: 1500, cx: 960, distortion: [0, 0]}\n"  // 11
    "  camera_sigma: {f: 15, cx: 3, distortion: [0.02, 0.01]}\n"                   // 12
    "  extrinsic:\n"                                                               // 13
    "    rotation_wxyz: [1, 0, 0, 0]\n"                                            // 14
    "    translation_m: [0.10, 0, 0]\n"                                            // 15
    "    sigma_rotation_deg: 2.0\n"                                                // 16
    "    sigma_translation_m: 0.05\n"                                              // 17
    "  time_offset_s: 0.0\n"                                                       // 18
    "  time_offset_sigma_s: 0.05\n"                                                // 19
    "ins:\n"                                                                       // 20
    "  file: nav/ins.csv\n"                                                        // 21
    "  camera_in_body:\n"                                                          // 22
    "    rotation_wxyz: [1, 0, 0, 0]\n"                                            // 23
    "    translation_m: [0.5, 0, 0.3]\n"                                           // 24
    "  sigma_horizontal_m: 0.5\n"                                                  // 25
    "  sigma_depth_m: 0.05\n"                                                      // 26
    "  sigma_attitude_deg: [0.05, 0.05, 0.2]\n"                                    // 27
    "origin: {lat: 43.0, lon: 5.0, depth: 0.0}\n"                                  // 28
    "lights:\n"                                                                    // 29
    "  response: uhi/lamp_response.csv\n"                                          // 30
    "  lamps:\n"                                                                   // 31
    "    - position_m: [-0.3, -0.3, 0.0]\n"                                        // 32
    "      axis: [0.0, 0.0, 1.0]\n"                                                // 33
    "    - position_m: [0.3, -0.3, 0.0]\n"                                         // 34
    "      axis: [0.0, 0.0, 1.0]\n";                                               // 35
// clang-format on

// kSurveyYamlV3 with `from` replaced by `to` (which must occur exactly once).
inline std::string surveyYamlV3With(const std::string& from, const std::string& to) {
  std::string text = kSurveyYamlV3;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at == std::string::npos) return text;
  EXPECT_EQ(text.find(from, at + 1), std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// A temporary survey.yaml holding variants of kSurveyYamlV3.
class SurveyYamlV3Test : public ::testing::Test {
 protected:
  TempFolder folder_{"config-v3"};
  std::filesystem::path path_ = folder_ / "survey.yaml";

  SurveyConfig readVariant(const std::string& from, const std::string& to) {
    writeText(path_, surveyYamlV3With(from, to));
    return readSurveyConfig(path_);
  }

  // The variant must be refused with exactly "<survey.yaml>:<rest>".
  void expectError(const std::string& from, const std::string& to, const std::string& rest) {
    writeText(path_, surveyYamlV3With(from, to));
    try {
      readSurveyConfig(path_);
      ADD_FAILURE() << "no InputError; expected " << rest;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path_.string() + ":" + rest);
      EXPECT_EQ(e.file(), path_);
    }
  }
};

}  // namespace hsmap::testing
