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
  EXPECT_EQ(config.rgb.vignetting.model, VignettingModel::none);
  EXPECT_FALSE(config.rgb.auto_gain.enabled);
  EXPECT_EQ(config.rgb.encoding.format, RgbFrameFormat::png);
}

TEST_F(RgbVideoSettingsYaml, EncodingFormats) {
  EXPECT_EQ(read("rgb: {encoding: {format: h264}}\n").rgb.encoding.format, RgbFrameFormat::h264);
  const RgbEncodingConfig jpeg = read("rgb: {encoding: {format: jpeg, jpeg_quality: 80}}\n").rgb.encoding;
  EXPECT_EQ(jpeg.format, RgbFrameFormat::jpeg);
  EXPECT_EQ(jpeg.jpeg_quality, 80);
  EXPECT_EQ(errorOf("rgb: {encoding: {format: mjpeg}}\n"),
            file() + ":line 3, key rgb.encoding.format: expected png, jpeg or h264, got 'mjpeg'");
  EXPECT_EQ(errorOf("rgb: {encoding: {format: h264, jpeg_quality: 80}}\n"),
            file() + ":line 3, key rgb.encoding.jpeg_quality: only allowed with format: jpeg");
  EXPECT_NE(errorOf("rgb: {encoding: {format: jpeg, jpeg_quality: 101}}\n").find("rgb.encoding.jpeg_quality"),
            std::string::npos);
  EXPECT_NE(errorOf("rgb: {width: 321, height: 180, encoding: {format: h264}}\n").find("even width"),
            std::string::npos);
}

TEST_F(RgbVideoSettingsYaml, VignettingModels) {
  EXPECT_EQ(read("rgb: {vignetting: {model: cos4}}\n").rgb.vignetting.model, VignettingModel::cos4);
  const RgbVignettingConfig polynomial =
      read("rgb:\n  vignetting: {model: polynomial, k: [-0.3, 0.05, 0]}\n").rgb.vignetting;
  EXPECT_EQ(polynomial.model, VignettingModel::polynomial);
  EXPECT_DOUBLE_EQ(polynomial.k[0], -0.3);
  EXPECT_DOUBLE_EQ(polynomial.k[1], 0.05);
  EXPECT_EQ(errorOf("rgb:\n  vignetting: {model: cos2}\n"),
            file() + ":line 4, key rgb.vignetting.model: expected none, cos4 or polynomial, got 'cos2'");
  EXPECT_EQ(errorOf("rgb:\n  vignetting: {model: cos4, k: [1, 2, 3]}\n"),
            file() + ":line 4, key rgb.vignetting.k: only allowed with model: polynomial");
  EXPECT_NE(errorOf("rgb:\n  vignetting: {model: polynomial}\n").find("rgb.vignetting.k"),
            std::string::npos);
}

TEST_F(RgbVideoSettingsYaml, AutoGainIsOnWhenGivenWithDefaults) {
  const RgbAutoGainConfig gain =
      read("rgb:\n  auto_gain: {step_db: 0.5, interval_s: 0.4, max_db: 12}\n").rgb.auto_gain;
  EXPECT_TRUE(gain.enabled);
  EXPECT_DOUBLE_EQ(gain.step_db, 0.5);
  EXPECT_DOUBLE_EQ(gain.interval_s, 0.4);
  EXPECT_DOUBLE_EQ(gain.max_db, 12.0);
  EXPECT_DOUBLE_EQ(gain.target_dn, RgbAutoGainConfig{}.target_dn);
  EXPECT_TRUE(read("rgb:\n  auto_gain: {}\n").rgb.auto_gain.enabled);
  EXPECT_EQ(errorOf("rgb:\n  auto_gain: {step: 1}\n"),
            file() + ":line 4, key rgb.auto_gain.step: unknown key; expected one of: target_dn, "
                     "step_db, interval_s, deadband_db, min_db, max_db, initial_db");
  EXPECT_EQ(errorOf("rgb:\n  auto_gain: {target_dn: 300}\n"),
            file() + ":line 4, key rgb.auto_gain.target_dn: expected a number in [1, 254], got 300");
  EXPECT_EQ(errorOf("rgb:\n  auto_gain: {min_db: 6, max_db: 3}\n"),
            file() + ":line 4, key rgb.auto_gain.max_db: expected max_db >= min_db");
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
