#include "pipelines/simulate/simulation_config.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "pipelines/simulate/simulation_config_yaml.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

TEST(SimulationPresets, EveryPresetIsValidAndNamedAsListed) {
  ASSERT_EQ(simulationPresetNames().size(), 5u);
  for (const std::string& name : simulationPresetNames()) {
    const auto config = simulationPreset(name);
    ASSERT_TRUE(config.has_value()) << name;
    EXPECT_EQ(config->preset, name);
    EXPECT_NO_THROW(validateSimulationConfig(*config)) << name;
  }
  EXPECT_FALSE(simulationPreset("huge").has_value());
}

TEST(SimulationPresets, DefaultResolutionsAndTinyLimits) {
  const SimulationConfig rugged = *simulationPreset("rugged");
  EXPECT_EQ(rugged.rgb.camera.width, 960);
  EXPECT_EQ(rugged.rgb.camera.height, 540);
  EXPECT_EQ(rugged.uhi.camera.samples, 1920);
  EXPECT_EQ(rugged.uhi.bands, 211);
  EXPECT_DOUBLE_EQ(rugged.uhi.wavelength_min_nm, 400.0);
  EXPECT_DOUBLE_EQ(rugged.uhi.wavelength_max_nm, 800.0);
  EXPECT_DOUBLE_EQ(rugged.motion.length_m, 20.0);
  EXPECT_EQ(rugged.scene.terrain, TerrainPreset::rugged);
  const SimulationConfig tiny = *simulationPreset("tiny");
  EXPECT_LE(tiny.uhi.bands, 32);
  EXPECT_EQ(simulationPreset("transect-100m")->motion.length_m, 100.0);
}

TEST(SimulationPresets, ScaledCamerasKeepTheFieldOfView) {
  const PinholeRadtanParameters full = scaledRgbCamera(960, 540);
  const PinholeRadtanParameters half = scaledRgbCamera(480, 270);
  EXPECT_NEAR(full.width / full.fx, half.width / half.fx, 1e-12);
  const PushbroomParameters uhi_full = scaledUhiCamera(1920);
  const PushbroomParameters uhi_small = scaledUhiCamera(240);
  EXPECT_NEAR(uhi_full.samples / uhi_full.f, uhi_small.samples / uhi_small.f, 1e-12);
}

TEST(SimulationPresets, ValidationNamesTheKnob) {
  SimulationConfig config = *simulationPreset("tiny");
  config.rgb.samples_per_pixel = 3;
  try {
    validateSimulationConfig(config);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "simulation setting rgb.samples_per_pixel: expected 1, 2 or 4");
  }
  config = *simulationPreset("tiny");
  config.motion.altitude_m = 0.1;
  EXPECT_THROW(validateSimulationConfig(config), std::invalid_argument);
}

class SimulationConfigYaml : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    const auto path = folder_.path() / "sim.yaml";
    std::ofstream(path) << text;
    return path;
  }
  std::string errorOf(const std::string& text) {
    try {
      readSimulationConfig(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  testing::TempFolder folder_;
};

TEST_F(SimulationConfigYaml, OverridesOnlyTheGivenKeys) {
  const SimulationConfig config = readSimulationConfig(write(
      "format: hsmap-simulation/1\n"
      "preset: rugged\n"
      "name: my-dive\n"
      "seed: 7\n"
      "motion: {length_m: 5, altitude_m: 2.5}\n"
      "rgb: {width: 480, height: 270, samples_per_pixel: 2}\n"
      "uhi: {samples: 480, bands: 50}\n"
      "calibration: {time_offset_s: -0.02, error_rotation_deg: 1}\n"
      "optics: {shadows: false}\n"));
  const SimulationConfig rugged = *simulationPreset("rugged");
  EXPECT_EQ(config.name, "my-dive");
  EXPECT_EQ(config.seed, 7u);
  EXPECT_DOUBLE_EQ(config.motion.length_m, 5.0);
  EXPECT_DOUBLE_EQ(config.motion.altitude_m, 2.5);
  EXPECT_DOUBLE_EQ(config.motion.speed_m_s, rugged.motion.speed_m_s);
  EXPECT_EQ(config.rgb.camera.width, 480);
  EXPECT_DOUBLE_EQ(config.rgb.camera.fx, scaledRgbCamera(480, 270).fx);
  EXPECT_EQ(config.rgb.samples_per_pixel, 2);
  EXPECT_EQ(config.uhi.camera.samples, 480);
  EXPECT_EQ(config.uhi.bands, 50);
  EXPECT_DOUBLE_EQ(config.calibration.time_offset_s, -0.02);
  EXPECT_DOUBLE_EQ(config.calibration.error_rotation_deg, 1.0);
  EXPECT_DOUBLE_EQ(config.calibration.error_translation_m, rugged.calibration.error_translation_m);
  EXPECT_FALSE(config.optics.shadows);
  EXPECT_EQ(config.scene.terrain, TerrainPreset::rugged);
}

TEST_F(SimulationConfigYaml, ErrorsNameTheFileLineAndKey) {
  const std::string file = (folder_.path() / "sim.yaml").string();
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: huge\n"),
            file + ":line 2, key preset: expected one of tiny, flat, low-relief, rugged, "
                   "transect-100m, got 'huge'");
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: tiny\nmotion: {lenght_m: 3}\n"),
            file + ":line 3, key motion.lenght_m: unknown key; expected one of: pattern, "
                   "length_m, speed_m_s, speed_variation, altitude_m, roll_pitch_amplitude_deg, "
                   "heading_wander_deg, lanes, lane_spacing_m, heading_deg");
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: tiny\noptics: {shadows: maybe}\n"),
            file + ":line 3, key optics.shadows: expected true or false, got 'maybe'");
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: tiny\nscene: {terrain: hilly}\n"),
            file + ":line 3, key scene.terrain: expected flat, low-relief or rugged, got 'hilly'");
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: tiny\nrgb: {samples_per_pixel: 3}\n"),
            file + ":line 3, key rgb.samples_per_pixel: expected 1, 2 or 4, got 3");
  EXPECT_EQ(errorOf("format: hsmap-simulation/2\npreset: tiny\n"),
            file + ":line 1, key format: expected hsmap-simulation/1, got 'hsmap-simulation/2'");
  EXPECT_EQ(errorOf("format: hsmap-simulation/1\npreset: tiny\nmotion: {altitude_m: 0.2}\n"),
            file + ": simulation setting motion.altitude_m: expected an altitude in [0.5, 10] m");
}

TEST_F(SimulationConfigYaml, NewSettingsDefaultToThePresetsBehaviour) {
  const SimulationConfig config =
      readSimulationConfig(write("format: hsmap-simulation/1\npreset: rugged\n"));
  EXPECT_EQ(config.motion.heading_deg, 0.0);
  EXPECT_EQ(config.scene.slope_deg, 0.0);
  EXPECT_EQ(config.scene.slope_direction_deg, 0.0);
  EXPECT_TRUE(config.ins.attitude);
  EXPECT_TRUE(config.rgb.blackouts.empty());
}

TEST_F(SimulationConfigYaml, ReadsHeadingSlopeAttitudeAndBlackouts) {
  const SimulationConfig config = readSimulationConfig(write(
      "format: hsmap-simulation/1\n"
      "preset: low-relief\n"
      "scene: {slope_deg: 12, slope_direction_deg: 125}\n"
      "motion: {heading_deg: 35}\n"
      "ins: {attitude: false}\n"
      "rgb:\n"
      "  blackouts:\n"
      "    - {start_s: 10, duration_s: 0.32}\n"
      "    - {start_s: 20.5, duration_s: 2}\n"));
  EXPECT_DOUBLE_EQ(config.scene.slope_deg, 12.0);
  EXPECT_DOUBLE_EQ(config.scene.slope_direction_deg, 125.0);
  EXPECT_DOUBLE_EQ(config.motion.heading_deg, 35.0);
  EXPECT_FALSE(config.ins.attitude);
  ASSERT_EQ(config.rgb.blackouts.size(), 2u);
  EXPECT_DOUBLE_EQ(config.rgb.blackouts[0].start_s, 10.0);
  EXPECT_DOUBLE_EQ(config.rgb.blackouts[0].duration_s, 0.32);
  EXPECT_DOUBLE_EQ(config.rgb.blackouts[1].start_s, 20.5);
  EXPECT_DOUBLE_EQ(config.rgb.blackouts[1].duration_s, 2.0);
  // The camera keeps the preset's size: blackouts alone do not replace it.
  EXPECT_EQ(config.rgb.camera.width, 960);
}

TEST_F(SimulationConfigYaml, NewSettingsOutOfRangeNameTheFileLineAndKey) {
  const std::string file = (folder_.path() / "sim.yaml").string();
  const std::string head = "format: hsmap-simulation/1\npreset: tiny\n";
  EXPECT_EQ(errorOf(head + "motion: {heading_deg: 400}\n"),
            file + ":line 3, key motion.heading_deg: expected a number in [-360, 360], got 400");
  EXPECT_EQ(errorOf(head + "scene: {slope_deg: 50}\n"),
            file + ":line 3, key scene.slope_deg: expected a number in [0, 45], got 50");
  EXPECT_EQ(errorOf(head + "scene: {slope_deg: -1}\n"),
            file + ":line 3, key scene.slope_deg: expected a number in [0, 45], got -1");
  EXPECT_EQ(errorOf(head + "scene: {slope_direction_deg: -361}\n"),
            file + ":line 3, key scene.slope_direction_deg: expected a number in [-360, 360], "
                   "got -361");
  EXPECT_EQ(errorOf(head + "ins: {attitude: no}\n"),
            file + ":line 3, key ins.attitude: expected true or false, got 'no'");
  EXPECT_EQ(errorOf(head + "rgb: {blackouts: 3}\n"),
            file + ":line 3, key rgb.blackouts: expected a list of {start_s, duration_s}, got '3'");
  EXPECT_EQ(errorOf(head + "rgb:\n  blackouts:\n    - {start_s: 1, duration_s: 1}\n"
                           "    - {start_s: 2, duration_s: 0}\n"),
            file + ":line 6, key rgb.blackouts[1].duration_s: expected a number > 0, got 0");
  EXPECT_EQ(errorOf(head + "rgb:\n  blackouts:\n    - {start_s: -1, duration_s: 1}\n"),
            file + ":line 5, key rgb.blackouts[0].start_s: expected a number in [0, 1e+06], got -1");
  EXPECT_EQ(errorOf(head + "rgb:\n  blackouts:\n    - {start: 1, duration_s: 1}\n"),
            file + ":line 5, key rgb.blackouts[0].start: unknown key; expected one of: start_s, "
                   "duration_s");
}

TEST(SimulationPresets, ValidationRejectsOutOfRangeNewSettings) {
  SimulationConfig config = *simulationPreset("tiny");
  config.rgb.blackouts.push_back({-0.5, 1.0});
  EXPECT_THROW(validateSimulationConfig(config), std::invalid_argument);
  config = *simulationPreset("tiny");
  config.scene.slope_deg = 46.0;
  EXPECT_THROW(validateSimulationConfig(config), std::invalid_argument);
  // 45 degrees along 100 m of track would lift the seabed out of the water.
  config = *simulationPreset("transect-100m");
  config.scene.slope_deg = 45.0;
  EXPECT_THROW(validateSimulationConfig(config), std::invalid_argument);
  config.scene.seabed_depth_m = 120.0;
  EXPECT_NO_THROW(validateSimulationConfig(config));
  config = *simulationPreset("tiny");
  config.motion.heading_deg = -361.0;
  EXPECT_THROW(validateSimulationConfig(config), std::invalid_argument);
}

// The simulation files the docs' benchmarks are made from stay readable as
// the settings evolve.
TEST(SimulationConfigFiles, TheBenchmarksConfigurationsReadAndValidate) {
  int read = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(HSMAP_SOURCE_DIR) / "benchmarks")) {
    if (entry.path().extension() != ".yaml") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.find("format: hsmap-simulation/1") == std::string::npos) continue;
    SimulationConfig config;
    ASSERT_NO_THROW(config = readSimulationConfig(entry.path())) << entry.path();
    EXPECT_NO_THROW(validateSimulationConfig(config)) << entry.path();
    ++read;
    if (entry.path().filename() == "lawnmower_south.yaml") {
      // What docs/BENCHMARKS.md says of it.
      EXPECT_EQ(config.motion.pattern, MotionPattern::lawnmower);
      EXPECT_EQ(config.motion.lanes, 2);
      EXPECT_LT(config.origin.lat_deg, 0.0);
      EXPECT_DOUBLE_EQ(config.calibration.time_offset_s, -0.02);
    }
  }
  EXPECT_GE(read, 2);
}

}  // namespace
}  // namespace hsmap
