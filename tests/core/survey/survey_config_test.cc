#include "core/survey/survey_config.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;
using testing::writeText;

// docs/SURVEY_FORMAT.md's example, with line numbers that the expected messages use.
// clang-format off
const char* const kValidYaml =
    "format: hsmap-survey/1\n"                                                     // 1
    "name: rugged-demo\n"                                                          // 2
    "rgb:\n"                                                                       // 3
    "  frames: rgb/frames.csv\n"                                                   // 4
    "  camera: {model: pinhole-radtan, width: 960, height: 540,\n"                 // 5
    "           fx: 800, fy: 810, cx: 480, cy: 270,"
    " distortion: [0.1, -0.05, 0.001, 0.002, 0.01]}\n"                             // 6
    "uhi:\n"                                                                       // 7
    "  cube: uhi/cube.hdr\n"                                                       // 8
    "  lines: uhi/lines.csv\n"                                                     // 9
    "  camera: {model: pushbroom, samples: 1920, f: 1500, cx: 960,"
    " distortion: [0.01, 0.002]}\n"                                                // 10
    "  extrinsic:\n"                                                               // 11
    "    rotation_wxyz: [1, 0, 0, 0]\n"                                            // 12
    "    translation_m: [0.10, 0, 0]\n"                                            // 13
    "    sigma_rotation_deg: 2.0\n"                                                // 14
    "    sigma_translation_m: 0.05\n"                                              // 15
    "  time_offset_s: 0.0\n"                                                       // 16
    "  time_offset_sigma_s: 0.05\n"                                                // 17
    "ins:\n"                                                                       // 18
    "  file: nav/ins.csv\n"                                                        // 19
    "  camera_in_body:\n"                                                          // 20
    "    rotation_wxyz: [1, 0, 0, 0]\n"                                            // 21
    "    translation_m: [0.5, 0, 0.3]\n"                                           // 22
    "  sigma_horizontal_m: 0.5\n"                                                  // 23
    "  sigma_depth_m: 0.05\n"                                                      // 24
    "  sigma_attitude_deg: [0.05, 0.05, 0.2]\n"                                    // 25
    "origin: {lat: 43.0, lon: 5.0, depth: 0.0}\n";                                 // 26
// clang-format on

class SurveyConfigTest : public ::testing::Test {
 protected:
  TempFolder folder_{"config"};
  std::filesystem::path path_ = folder_ / "survey.yaml";

  // Writes kValidYaml with `from` replaced by `to` (must occur exactly once).
  void writeVariant(const std::string& from, const std::string& to) {
    std::string text = kValidYaml;
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    ASSERT_EQ(text.find(from, at + 1), std::string::npos) << from;
    text.replace(at, from.size(), to);
    writeText(path_, text);
  }

  // readSurveyConfig must throw exactly "<survey.yaml>:<rest>".
  void expectError(const std::string& rest) {
    try {
      readSurveyConfig(path_);
      FAIL() << "no InputError; expected " << rest;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), path_.string() + ":" + rest);
      EXPECT_EQ(e.file(), path_);
    }
  }
};

TEST_F(SurveyConfigTest, ReadsDatasetExample) {
  writeText(path_, kValidYaml);
  const SurveyConfig config = readSurveyConfig(path_);
  EXPECT_EQ(config.name, "rugged-demo");
  EXPECT_EQ(config.rgb.frames, "rgb/frames.csv");
  EXPECT_FALSE(config.rgb.video.has_value());
  EXPECT_EQ(config.rgb.camera.width, 960);
  EXPECT_EQ(config.rgb.camera.height, 540);
  EXPECT_EQ(config.rgb.camera.fx, 800.0);
  EXPECT_EQ(config.rgb.camera.fy, 810.0);
  EXPECT_EQ(config.rgb.camera.cx, 480.0);
  EXPECT_EQ(config.rgb.camera.cy, 270.0);
  EXPECT_EQ(config.rgb.camera.distortion, (std::array<double, 5>{0.1, -0.05, 0.001, 0.002, 0.01}));
  EXPECT_EQ(config.uhi.cube, "uhi/cube.hdr");
  EXPECT_EQ(config.uhi.lines, "uhi/lines.csv");
  EXPECT_EQ(config.uhi.camera.samples, 1920);
  EXPECT_EQ(config.uhi.camera.f, 1500.0);
  EXPECT_EQ(config.uhi.camera.cx, 960.0);
  EXPECT_EQ(config.uhi.camera.distortion, (std::array<double, 2>{0.01, 0.002}));
  EXPECT_EQ(config.uhi.T_C_U.rotation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(config.uhi.T_C_U.translation_m, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_EQ(config.uhi.sigma_rotation_deg, 2.0);
  EXPECT_EQ(config.uhi.sigma_translation_m, 0.05);
  EXPECT_EQ(config.uhi.time_offset_s, 0.0);
  EXPECT_EQ(config.uhi.time_offset_sigma_s, 0.05);
  EXPECT_EQ(config.ins.file, "nav/ins.csv");
  EXPECT_EQ(config.ins.T_B_C.translation_m, Eigen::Vector3d(0.5, 0, 0.3));
  EXPECT_EQ(config.ins.sigma_horizontal_m, 0.5);
  EXPECT_EQ(config.ins.sigma_depth_m, 0.05);
  EXPECT_EQ(config.ins.sigma_attitude_deg, (std::array<double, 3>{0.05, 0.05, 0.2}));
  ASSERT_TRUE(config.origin.has_value());
  EXPECT_EQ(config.origin->lat_deg, 43.0);
  EXPECT_EQ(config.origin->lon_deg, 5.0);
  EXPECT_EQ(config.origin->depth_m, 0.0);
}

TEST_F(SurveyConfigTest, OptionalKeysTakeDocumentedDefaults) {
  writeText(
      path_,
      "format: hsmap-survey/1\n"
      "name: minimal\n"
      "rgb:\n"
      "  frames: rgb/frames.csv\n"
      "  camera: {model: pinhole-radtan, width: 64, height: 48, fx: 50, fy: 50, cx: 32, cy: 24}\n"
      "uhi:\n"
      "  cube: uhi/cube.hdr\n"
      "  lines: uhi/lines.csv\n"
      "  camera: {model: pushbroom, samples: 32, f: 40, cx: 16}\n"
      "  extrinsic: {rotation_wxyz: [1, 0, 0, 0], translation_m: [0, 0, 0]}\n"
      "ins:\n"
      "  file: nav/ins.csv\n"
      "  camera_in_body: {rotation_wxyz: [1, 0, 0, 0], translation_m: [0, 0, 0]}\n");
  const SurveyConfig config = readSurveyConfig(path_);
  EXPECT_EQ(config.rgb.camera.distortion, (std::array<double, 5>{0, 0, 0, 0, 0}));
  EXPECT_EQ(config.uhi.camera.distortion, (std::array<double, 2>{0, 0}));
  EXPECT_EQ(config.uhi.sigma_rotation_deg, 2.0);
  EXPECT_EQ(config.uhi.sigma_translation_m, 0.05);
  EXPECT_EQ(config.uhi.time_offset_s, 0.0);
  EXPECT_EQ(config.uhi.time_offset_sigma_s, 0.05);
  EXPECT_EQ(config.ins.sigma_horizontal_m, 0.5);
  EXPECT_EQ(config.ins.sigma_depth_m, 0.05);
  EXPECT_EQ(config.ins.sigma_attitude_deg, (std::array<double, 3>{0.05, 0.05, 0.2}));
  EXPECT_FALSE(config.origin.has_value());
}

TEST_F(SurveyConfigTest, ReadsVideoSource) {
  writeVariant("  frames: rgb/frames.csv\n",
               "  video: rgb/dive.mp4\n  start_time: 12.5\n  fps: 25\n");
  const SurveyConfig config = readSurveyConfig(path_);
  ASSERT_TRUE(config.rgb.video.has_value());
  EXPECT_TRUE(config.rgb.frames.empty());
  EXPECT_EQ(config.rgb.video->video, "rgb/dive.mp4");
  EXPECT_EQ(config.rgb.video->start_time, 12.5);
  EXPECT_EQ(config.rgb.video->fps, 25.0);
}

TEST_F(SurveyConfigTest, NormalisesNearlyUnitQuaternions) {
  writeVariant("    rotation_wxyz: [1, 0, 0, 0]\n    translation_m: [0.5",
               "    rotation_wxyz: [0.7071, 0, 0, 0.7071]\n    translation_m: [0.5");
  const SurveyConfig config = readSurveyConfig(path_);
  EXPECT_NEAR(config.ins.T_B_C.rotation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(config.ins.T_B_C.rotation.w(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(config.ins.T_B_C.rotation.z(), std::sqrt(0.5), 1e-15);
}

TEST_F(SurveyConfigTest, WriteThenReadIsIdentity) {
  SurveyConfig config;
  config.name = "round: trip";  // needs quoting in YAML
  config.rgb.frames = "rgb/frames.csv";
  config.rgb.camera = {
      1920, 1080, 1400.123456789, 1401.5, 959.5, 539.25, {-0.1, 0.01, 1e-4, -2e-4, 3e-7}};
  config.uhi.cube = "uhi/cube.hdr";
  config.uhi.lines = "uhi/lines.csv";
  config.uhi.camera = {1920, 1500.0 / 3.0, 960.1, {0.02, -0.003}};
  config.uhi.T_C_U.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 0.5).normalized()));
  config.uhi.T_C_U.translation_m = Eigen::Vector3d(0.1, -0.02, 1.0 / 3.0);
  config.uhi.sigma_rotation_deg = 1.5;
  config.uhi.sigma_translation_m = 0.02;
  config.uhi.time_offset_s = 0.0151;
  config.uhi.time_offset_sigma_s = 0.01;
  config.ins.file = "nav/ins.csv";
  config.ins.T_B_C.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  config.ins.T_B_C.translation_m = Eigen::Vector3d(0.5, 0.0, 0.3);
  config.ins.sigma_horizontal_m = 0.75;
  config.ins.sigma_depth_m = 0.1;
  config.ins.sigma_attitude_deg = {0.01, 0.02, 0.3};
  config.origin = GeodeticPoint{43.123456789, -5.000001, 12.5};

  writeSurveyConfig(path_, config);
  EXPECT_FALSE(std::filesystem::exists(path_.string() + ".partial"));
  const SurveyConfig back = readSurveyConfig(path_);
  EXPECT_EQ(back.name, config.name);
  EXPECT_EQ(back.rgb.frames, config.rgb.frames);
  EXPECT_FALSE(back.rgb.video.has_value());
  EXPECT_EQ(back.rgb.camera.width, config.rgb.camera.width);
  EXPECT_EQ(back.rgb.camera.height, config.rgb.camera.height);
  EXPECT_EQ(back.rgb.camera.fx, config.rgb.camera.fx);
  EXPECT_EQ(back.rgb.camera.fy, config.rgb.camera.fy);
  EXPECT_EQ(back.rgb.camera.cx, config.rgb.camera.cx);
  EXPECT_EQ(back.rgb.camera.cy, config.rgb.camera.cy);
  EXPECT_EQ(back.rgb.camera.distortion, config.rgb.camera.distortion);
  EXPECT_EQ(back.uhi.cube, config.uhi.cube);
  EXPECT_EQ(back.uhi.lines, config.uhi.lines);
  EXPECT_EQ(back.uhi.camera.samples, config.uhi.camera.samples);
  EXPECT_EQ(back.uhi.camera.f, config.uhi.camera.f);
  EXPECT_EQ(back.uhi.camera.cx, config.uhi.camera.cx);
  EXPECT_EQ(back.uhi.camera.distortion, config.uhi.camera.distortion);
  EXPECT_EQ(back.uhi.T_C_U.rotation.coeffs(), config.uhi.T_C_U.rotation.coeffs());
  EXPECT_EQ(back.uhi.T_C_U.translation_m, config.uhi.T_C_U.translation_m);
  EXPECT_EQ(back.uhi.sigma_rotation_deg, config.uhi.sigma_rotation_deg);
  EXPECT_EQ(back.uhi.sigma_translation_m, config.uhi.sigma_translation_m);
  EXPECT_EQ(back.uhi.time_offset_s, config.uhi.time_offset_s);
  EXPECT_EQ(back.uhi.time_offset_sigma_s, config.uhi.time_offset_sigma_s);
  EXPECT_EQ(back.ins.file, config.ins.file);
  EXPECT_EQ(back.ins.T_B_C.rotation.coeffs(), config.ins.T_B_C.rotation.coeffs());
  EXPECT_EQ(back.ins.T_B_C.translation_m, config.ins.T_B_C.translation_m);
  EXPECT_EQ(back.ins.sigma_horizontal_m, config.ins.sigma_horizontal_m);
  EXPECT_EQ(back.ins.sigma_depth_m, config.ins.sigma_depth_m);
  EXPECT_EQ(back.ins.sigma_attitude_deg, config.ins.sigma_attitude_deg);
  ASSERT_TRUE(back.origin.has_value());
  EXPECT_EQ(back.origin->lat_deg, config.origin->lat_deg);
  EXPECT_EQ(back.origin->lon_deg, config.origin->lon_deg);
  EXPECT_EQ(back.origin->depth_m, config.origin->depth_m);

  // Writing what was read gives the same text: the file is a fixed point.
  const std::string first_text = testing::readText(path_);
  writeSurveyConfig(path_, back);
  EXPECT_EQ(testing::readText(path_), first_text);
}

// Contract v3's optional camera_sigma and lights survive a write and a read
// bit-exactly, and a survey without them is written without them.
TEST_F(SurveyConfigTest, WriteThenReadIsIdentityWithCameraSigmasAndLights) {
  writeText(path_, kValidYaml);
  SurveyConfig config = readSurveyConfig(path_);
  config.rgb.camera_sigma = PinholeRadtanSigma{8.0 / 3.0, 8.1, 0.0, 4e-5, {0.02, 0.0, 1e-3, 0.1 / 3.0, 1000.0}};
  config.uhi.camera_sigma = PushbroomSigma{15.000000000000002, 1e6, {0.02, 0.01}};
  LightsConfig lights;
  lights.response = "uhi/lamp_response.csv";
  lights.lamps.push_back({Eigen::Vector3d(-0.3, -0.3, 0.0), Eigen::Vector3d::UnitZ()});
  lights.lamps.push_back({Eigen::Vector3d(0.1 / 3.0, -100.0, 1e-9),
                          Eigen::Vector3d(1.0, -2.0, 0.3).normalized()});
  config.lights = lights;

  writeSurveyConfig(path_, config);
  const SurveyConfig back = readSurveyConfig(path_);
  ASSERT_TRUE(back.rgb.camera_sigma.has_value());
  EXPECT_EQ(back.rgb.camera_sigma->fx, config.rgb.camera_sigma->fx);
  EXPECT_EQ(back.rgb.camera_sigma->fy, config.rgb.camera_sigma->fy);
  EXPECT_EQ(back.rgb.camera_sigma->cx, config.rgb.camera_sigma->cx);
  EXPECT_EQ(back.rgb.camera_sigma->cy, config.rgb.camera_sigma->cy);
  EXPECT_EQ(back.rgb.camera_sigma->distortion, config.rgb.camera_sigma->distortion);
  ASSERT_TRUE(back.uhi.camera_sigma.has_value());
  EXPECT_EQ(back.uhi.camera_sigma->f, config.uhi.camera_sigma->f);
  EXPECT_EQ(back.uhi.camera_sigma->cx, config.uhi.camera_sigma->cx);
  EXPECT_EQ(back.uhi.camera_sigma->distortion, config.uhi.camera_sigma->distortion);
  ASSERT_TRUE(back.lights.has_value());
  EXPECT_EQ(back.lights->response, lights.response);
  ASSERT_EQ(back.lights->lamps.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.lights->lamps[i].p_C, lights.lamps[i].p_C) << i;
    EXPECT_EQ(back.lights->lamps[i].axis_C, lights.lamps[i].axis_C) << i;
  }
  const std::string first_text = testing::readText(path_);
  writeSurveyConfig(path_, back);
  EXPECT_EQ(testing::readText(path_), first_text);

  config.rgb.camera_sigma.reset();
  config.uhi.camera_sigma.reset();
  config.lights.reset();
  writeSurveyConfig(path_, config);
  const std::string without = testing::readText(path_);
  EXPECT_EQ(without.find("camera_sigma"), std::string::npos) << without;
  EXPECT_EQ(without.find("lights"), std::string::npos) << without;
  const SurveyConfig plain = readSurveyConfig(path_);
  EXPECT_FALSE(plain.rgb.camera_sigma || plain.uhi.camera_sigma || plain.lights);
}

TEST_F(SurveyConfigTest, WriterRefusesInvalidLightsAndSigmas) {
  writeText(path_, kValidYaml);
  const SurveyConfig valid = readSurveyConfig(path_);
  const auto other = folder_ / "other.yaml";
  SurveyConfig config = valid;
  config.lights = LightsConfig{"uhi/lamp_response.csv", {}};  // no lamp
  EXPECT_THROW(writeSurveyConfig(other, config), std::invalid_argument);
  config.lights->lamps.push_back({Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2)});
  EXPECT_THROW(writeSurveyConfig(other, config), std::invalid_argument);
  config = valid;
  config.uhi.camera_sigma = PushbroomSigma{-1.0, 0.0, {0.0, 0.0}};
  EXPECT_THROW(writeSurveyConfig(other, config), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(other));
}

TEST_F(SurveyConfigTest, WriteThenReadVideoSourceWithoutOrigin) {
  writeVariant("  frames: rgb/frames.csv\n",
               "  video: rgb/dive.mp4\n  start_time: 1700000000.04\n  fps: 29.97\n");
  SurveyConfig config = readSurveyConfig(path_);
  config.origin.reset();
  writeSurveyConfig(path_, config);
  const SurveyConfig back = readSurveyConfig(path_);
  ASSERT_TRUE(back.rgb.video.has_value());
  EXPECT_EQ(back.rgb.video->video, "rgb/dive.mp4");
  EXPECT_EQ(back.rgb.video->start_time, 1700000000.04);
  EXPECT_EQ(back.rgb.video->fps, 29.97);
  EXPECT_FALSE(back.origin.has_value());
}

TEST_F(SurveyConfigTest, WriterRefusesInvalidConfiguration) {
  writeText(path_, kValidYaml);
  SurveyConfig config = readSurveyConfig(path_);
  config.rgb.camera.fx = -1.0;
  const auto other = folder_ / "other.yaml";
  EXPECT_THROW(writeSurveyConfig(other, config), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(other));
  config = readSurveyConfig(path_);
  config.rgb.video = RgbVideoConfig{"rgb/v.mp4", 0.0, 25.0};
  EXPECT_THROW(writeSurveyConfig(other, config), std::invalid_argument);
}

// ---- each bad key, type, range: the exact message --------------------------

TEST_F(SurveyConfigTest, UnknownTopLevelKey) {
  writeText(path_, std::string(kValidYaml) + "colour: red\n");
  expectError(
      "line 27, key colour: unknown key; expected one of: format, name, rgb, uhi, ins, origin, "
      "lights");
}

TEST_F(SurveyConfigTest, UnknownNestedKey) {
  writeVariant("    sigma_rotation_deg: 2.0", "    sigma_rotaton_deg: 2.0");
  expectError(
      "line 14, key uhi.extrinsic.sigma_rotaton_deg: unknown key; expected one of: "
      "rotation_wxyz, translation_m, sigma_rotation_deg, sigma_translation_m");
}

TEST_F(SurveyConfigTest, UnknownKeyInFlowMap) {
  writeVariant("fx: 800, fy: 810", "fx: 800, fy: 810, skew: 0");
  expectError(
      "line 6, key rgb.camera.skew: unknown key; expected one of: model, width, height, "
      "fx, fy, cx, cy, distortion");
}

TEST_F(SurveyConfigTest, DuplicatedKey) {
  writeVariant("  time_offset_s: 0.0\n", "  time_offset_s: 0.0\n  time_offset_s: 0.1\n");
  expectError("line 17, key uhi.time_offset_s: duplicated key (first given at line 16)");
}

TEST_F(SurveyConfigTest, MissingRequiredKeys) {
  writeVariant("  lines: uhi/lines.csv\n", "");
  expectError("line 8, key uhi.lines: missing required key");
  writeVariant("name: rugged-demo\n", "");
  expectError("line 1, key name: missing required key");
  writeVariant("    translation_m: [0.5, 0, 0.3]\n", "");
  expectError("line 21, key ins.camera_in_body.translation_m: missing required key");
  writeVariant("  frames: rgb/frames.csv\n", "");
  expectError(
      "line 4, key rgb.frames: missing required key: give 'frames' (a frames.csv) or 'video'");
}

TEST_F(SurveyConfigTest, WrongTypes) {
  writeVariant("fx: 800", "fx: abc");
  expectError("line 6, key rgb.camera.fx: expected a number, got 'abc'");
  writeVariant("width: 960", "width: 960.5");
  expectError("line 5, key rgb.camera.width: expected an integer, got '960.5'");
  writeVariant("  cube: uhi/cube.hdr", "  cube: [a, b]");
  expectError("line 8, key uhi.cube: expected a non-empty text value, got a list");
  writeVariant("    translation_m: [0.10, 0, 0]", "    translation_m: 0.1");
  expectError("line 13, key uhi.extrinsic.translation_m: expected a list of 3 numbers, got '0.1'");
  writeVariant("    translation_m: [0.10, 0, 0]", "    translation_m: [0.10, x, 0]");
  expectError("line 13, key uhi.extrinsic.translation_m[1]: expected a number, got 'x'");
  writeVariant("  time_offset_s: 0.0", "  time_offset_s: nan");
  expectError("line 16, key uhi.time_offset_s: expected a finite number, got 'nan'");
  writeVariant("  time_offset_s: 0.0", "  time_offset_s:");
  expectError("line 16, key uhi.time_offset_s: expected a number, got nothing");
  writeVariant("ins:\n  file: nav/ins.csv\n", "ins:\n  file: nav/ins.csv\n  camera_in_body: 3\n");
  expectError("line 21, key ins.camera_in_body: duplicated key (first given at line 20)");
}

TEST_F(SurveyConfigTest, SectionThatIsNotAMap) {
  writeVariant("origin: {lat: 43.0, lon: 5.0, depth: 0.0}", "origin: 43.0");
  expectError("line 26, key origin: expected a map with keys (lat, lon, depth), got '43.0'");
}

TEST_F(SurveyConfigTest, ValuesOutOfRange) {
  writeVariant("fy: 810", "fy: -810");
  expectError("line 6, key rgb.camera.fy: expected a number > 0, got -810");
  writeVariant("width: 960", "width: 0");
  expectError("line 5, key rgb.camera.width: expected an integer > 0, got 0");
  writeVariant("samples: 1920", "samples: -5");
  expectError("line 10, key uhi.camera.samples: expected an integer > 0, got -5");
  writeVariant("f: 1500", "f: 0");
  expectError("line 10, key uhi.camera.f: expected a number > 0, got 0");
  writeVariant("  sigma_depth_m: 0.05", "  sigma_depth_m: 0");
  expectError("line 24, key ins.sigma_depth_m: expected a number > 0, got 0");
  writeVariant("  time_offset_sigma_s: 0.05", "  time_offset_sigma_s: -0.05");
  expectError("line 17, key uhi.time_offset_sigma_s: expected a number > 0, got -0.05");
  writeVariant("  sigma_attitude_deg: [0.05, 0.05, 0.2]", "  sigma_attitude_deg: [0.05, -1, 0.2]");
  expectError(
      "line 25, key ins.sigma_attitude_deg: expected three numbers in (0, 180], got -1 at position 2");
  writeVariant("lat: 43.0", "lat: 95");
  expectError("line 26, key origin.lat: expected a number in [-90, 90], got 95");
  writeVariant("lon: 5.0", "lon: 181");
  expectError("line 26, key origin.lon: expected a number in [-180, 180], got 181");
}

TEST_F(SurveyConfigTest, DistortionListLengths) {
  writeVariant("distortion: [0.1, -0.05, 0.001, 0.002, 0.01]", "distortion: [0.1, -0.05]");
  expectError("line 6, key rgb.camera.distortion: expected a list of 5 numbers, got a list of 2");
  writeVariant("distortion: [0.01, 0.002]", "distortion: [0.01, 0.002, 0.0]");
  expectError("line 10, key uhi.camera.distortion: expected a list of 2 numbers, got a list of 3");
}

TEST_F(SurveyConfigTest, QuaternionFarFromUnitNorm) {
  writeVariant("    rotation_wxyz: [1, 0, 0, 0]\n    translation_m: [0.10",
               "    rotation_wxyz: [1, 0.1, 0, 0]\n    translation_m: [0.10");
  expectError(
      "line 12, key uhi.extrinsic.rotation_wxyz: expected a unit quaternion [w, x, y, z] "
      "(norm within 0.001 of 1), got norm 1.004987562112089");
}

TEST_F(SurveyConfigTest, UnsupportedFormatAndModels) {
  writeVariant("format: hsmap-survey/1", "format: hsmap-survey/2");
  expectError("line 1, key format: unsupported format 'hsmap-survey/2'; expected 'hsmap-survey/1'");
  writeVariant("model: pinhole-radtan", "model: pinhole-equidistant");
  expectError(
      "line 5, key rgb.camera.model: unsupported camera model 'pinhole-equidistant'; "
      "expected 'pinhole-radtan'");
  writeVariant("model: pushbroom", "model: frame");
  expectError(
      "line 10, key uhi.camera.model: unsupported camera model 'frame'; expected 'pushbroom'");
}

TEST_F(SurveyConfigTest, RgbSourceRules) {
  writeVariant("  frames: rgb/frames.csv\n", "  frames: rgb/frames.csv\n  video: rgb/dive.mp4\n");
  expectError("line 5, key rgb.video: give either 'frames' (a frames.csv) or 'video', not both");
  writeVariant("  frames: rgb/frames.csv\n", "  video: rgb/dive.mp4\n  start_time: 3\n");
  expectError("line 4, key rgb.fps: missing required key");
  writeVariant("  frames: rgb/frames.csv\n", "  frames: rgb/frames.csv\n  fps: 25\n");
  expectError("line 5, key rgb.fps: only allowed together with 'video'");
  writeVariant("  frames: rgb/frames.csv\n", "  video: rgb/dive.mp4\n  start_time: 3\n  fps: 0\n");
  expectError("line 6, key rgb.fps: expected a number > 0, got 0");
}

TEST_F(SurveyConfigTest, YamlSyntaxErrorNamesTheLine) {
  writeVariant("distortion: [0.01, 0.002]}", "distortion: [0.01, 0.002}");
  expectError("line 10: YAML syntax error: illegal flow end");
}

TEST_F(SurveyConfigTest, EmptyFileAndNonMapDocument) {
  writeText(path_, "");
  expectError("line 1: empty file; expected a YAML map starting with 'format: hsmap-survey/1'");
  writeText(path_, "- a\n- b\n");
  expectError(
      "line 1: expected a map with keys (format, name, rgb, uhi, ins, origin, lights), got a "
      "list");
}

TEST_F(SurveyConfigTest, MissingFile) {
  try {
    readSurveyConfig(folder_ / "absent.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (folder_ / "absent.yaml").string() +
                                         ": file not found");
  }
}

}  // namespace
}  // namespace hsmap
