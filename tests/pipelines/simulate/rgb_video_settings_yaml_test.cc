// The simulation file's settings of the RGB video effects (docs/SIMULATOR.md):
// absent, they leave the preset's behaviour; given, they are read; wrong,
// they are errors naming the file, line and key.
#include <fstream>

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "pipelines/simulate/simulation_config_yaml.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

class RgbVideoSettingsYaml : public ::testing::Test {
 protected:
  SimulationConfig read(const std::string& body) {
    std::ofstream(path()) << "format: hsmap-simulation/1\npreset: rugged\n" << body;
    return readSimulationConfig(path());
  }
  // The error of `body` (after the two lines of format and preset).
  std::string errorOf(const std::string& body) {
    try {
      read(body);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  std::string file() const { return path().string(); }
  std::filesystem::path path() const { return folder_.path() / "sim.yaml"; }
  testing::TempFolder folder_;
};

TEST_F(RgbVideoSettingsYaml, AbsentSettingsLeaveEveryEffectOff) {
  const SimulationConfig config = read("");
  EXPECT_EQ(config.rgb.exposure_s, 0.0);
}

TEST_F(RgbVideoSettingsYaml, MotionBlurExposure) {
  EXPECT_DOUBLE_EQ(read("rgb: {exposure_s: 0.02}\n").rgb.exposure_s, 0.02);
  EXPECT_EQ(errorOf("rgb: {exposure_s: 0.05}\n"),
            file() + ":line 3, key rgb.exposure_s: expected a number in [0, 0.04], got 0.05");
  EXPECT_EQ(errorOf("rgb: {exposure_s: -0.01}\n"),
            file() + ":line 3, key rgb.exposure_s: expected a number in [0, 0.04], got -0.01");
}

}  // namespace
}  // namespace hsmap
