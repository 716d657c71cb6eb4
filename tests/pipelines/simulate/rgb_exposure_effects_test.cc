// Vignetting (rgb.vignetting) and automatic gain (rgb.auto_gain), each
// checked against its model on a short, noise-free `tiny`: a frame divided by
// the same frame without the effect is the stated falloff (the scene divides
// out, as if it were flat and uniform), and the gain steps at the stated
// frames by the stated size, as the metering rule decides.
#include <algorithm>
#include <cmath>
#include <memory>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "core/survey/csv_table.h"
#include "core/survey/survey.h"
#include "pipelines/simulate/rgb_auto_gain.h"
#include "pipelines/simulate/rgb_vignetting.h"
#include "pipelines/simulate/simulate_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

// A short `tiny` with small frames and no sensor noise.
SimulationConfig noiseFreeTiny() {
  SimulationConfig config = *simulationPreset("tiny");
  config.motion.length_m = 0.9;
  config.rgb.camera = scaledRgbCamera(160, 90);
  config.rgb.read_noise_dn = 0.0;
  config.rgb.electrons_per_dn = 1e12;
  return config;
}

struct Simulated {
  testing::TempFolder folder{"rgb_exposure_effects"};
  Survey survey;
};

std::unique_ptr<Simulated> simulate(const SimulationConfig& config) {
  auto simulated = std::make_unique<Simulated>();
  std::ostringstream log;
  simulateSurvey(config, simulated->folder / "survey", log);
  simulated->survey = loadSurvey(simulated->folder / "survey");
  return simulated;
}

const Survey& reference() {
  static const std::unique_ptr<Simulated> survey = simulate(noiseFreeTiny());
  return survey->survey;
}

// Checks every pixel of frame k whose reference value is at least 30 DN and
// whose values are below saturation: value / reference = expected(u, v), up to
// the rounding of both to whole DN. Returns the number of pixels checked.
template <class Expected>
int expectRatio(const Survey& survey, int k, Expected expected) {
  const cv::Mat frame = survey.rgb.frame(k);
  const cv::Mat base = reference().rgb.frame(k);
  int checked = 0, wrong = 0;
  for (int v = 0; v < frame.rows; ++v) {
    for (int u = 0; u < frame.cols; ++u) {
      for (int c = 0; c < 3; ++c) {
        const double value = frame.at<cv::Vec3b>(v, u)[c];
        const double base_value = base.at<cv::Vec3b>(v, u)[c];
        if (base_value < 30.0 || base_value >= 255.0 || value >= 255.0) continue;
        const double factor = expected(u, v);
        // |value - x f| <= 0.5 and |base - x| <= 0.5 for the unrounded x.
        const double tolerance = (0.5 + 0.5 * factor) / base_value + 1e-4;
        if (std::abs(value / base_value - factor) > tolerance) ++wrong;
        ++checked;
      }
    }
  }
  EXPECT_EQ(wrong, 0) << "frame " << k << ": " << wrong << " of " << checked << " pixels";
  return checked;
}

TEST(RgbExposureEffects, VignettingIsTheStatedFalloff) {
  for (const RgbVignettingConfig vignetting :
       {RgbVignettingConfig{VignettingModel::cos4, {0.0, 0.0, 0.0}},
        RgbVignettingConfig{VignettingModel::polynomial, {-0.35, 0.1, -0.05}}}) {
    SimulationConfig config = noiseFreeTiny();
    config.rgb.vignetting = vignetting;
    const auto simulated = simulate(config);
    ASSERT_EQ(simulated->survey.rgb.frameCount(), reference().rgb.frameCount());
    const PinholeRadtanParameters& camera = config.rgb.camera;
    for (int k : {0, simulated->survey.rgb.frameCount() / 2}) {
      const int checked = expectRatio(simulated->survey, k, [&](int u, int v) {
        return vignettingFactor(vignetting, camera, u, v);
      });
      EXPECT_GT(checked, 20000);
    }
    // The falloff is real: a corner gets markedly less than the centre.
    const double corner = vignettingFactor(vignetting, camera, 0, 0);
    EXPECT_LT(corner, 0.75);
    EXPECT_NEAR(vignettingFactor(vignetting, camera, camera.cx, camera.cy), 1.0, 1e-12);
  }
  // cos^4 of the presets' 62 x 37 degree camera in its corner (half-angles
  // 31.0 and 18.5 degrees: tan^2 sum 0.472 -> cos^2 = 1 / 1.472).
  EXPECT_NEAR(vignettingFactor({VignettingModel::cos4, {}}, scaledRgbCamera(960, 540), 0, 0),
              std::pow(1.0 / 1.472, 2.0), 0.03);
}

TEST(RgbExposureEffects, AutoGainStepsAtTheStatedFramesByTheStatedSize) {
  SimulationConfig config = noiseFreeTiny();
  RgbAutoGainConfig& gain = config.rgb.auto_gain;
  gain.enabled = true;
  gain.target_dn = 200.0;  // far above the scene's brightness: the gain climbs
  gain.step_db = 1.5;
  gain.interval_s = 0.2;   // 5 frames at 25 Hz
  gain.deadband_db = 0.5;
  gain.max_db = 3.0;
  const auto simulated = simulate(config);
  const Survey& survey = simulated->survey;

  const CsvTable table = readCsvTable(simulated->folder / "survey" / "truth" / "rgb_gain.csv", {{"t", "gain_db"}});
  ASSERT_EQ(table.rows.size(), std::size_t(survey.rgb.frameCount()));
  std::vector<double> gains_db;
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    EXPECT_EQ(std::stod(table.rows[k].cells[0]), survey.rgb.time(int(k)));
    gains_db.push_back(std::stod(table.rows[k].cells[1]));
  }
  EXPECT_EQ(gains_db.front(), 0.0);

  // Replay the camera's rule on the frames it wrote: each metering frame's
  // mean decides the next frame's gain; nothing else changes it.
  const int period = 5;
  int steps = 0;
  for (int k = 0; k + 1 < survey.rgb.frameCount(); ++k) {
    const double change = gains_db[k + 1] - gains_db[k];
    if ((k + 1) % period != 0) {
      EXPECT_EQ(change, 0.0) << "frame " << k + 1 << " is not a metering step";
      continue;
    }
    const cv::Scalar mean = cv::mean(survey.rgb.frame(k));
    const double error_db = 20.0 * std::log10(200.0 / ((mean[0] + mean[1] + mean[2]) / 3.0));
    double expected = 0.0;
    if (std::abs(error_db) > 0.5) expected = error_db > 0.0 ? 1.5 : -1.5;
    expected = std::clamp(gains_db[k] + expected, 0.0, 3.0) - gains_db[k];
    EXPECT_NEAR(change, expected, 1e-12) << "frame " << k + 1 << ", error " << error_db << " dB";
    if (change != 0.0) {
      // At the stated time: a whole number of intervals after the first frame.
      const double intervals = (survey.rgb.time(k + 1) - survey.rgb.time(0)) / 0.2;
      EXPECT_NEAR(intervals, std::round(intervals), 1e-6);
      ++steps;
    }
  }
  // Dark against a 200 DN target (the scene's mean is about 120 DN): it
  // climbs 1.5 dB at frames 5 and 10 to its 3 dB limit and stays there.
  EXPECT_EQ(gains_db[4], 0.0);
  EXPECT_EQ(gains_db[5], 1.5);
  EXPECT_EQ(gains_db[9], 1.5);
  EXPECT_EQ(gains_db[10], 3.0);
  EXPECT_EQ(gains_db.back(), 3.0);
  EXPECT_EQ(steps, 2);

  // Every frame is the fixed-exposure frame times its gain.
  for (int k : {0, 7, 12, 24, survey.rgb.frameCount() - 1}) {
    const double factor = std::pow(10.0, gains_db[k] / 20.0);
    EXPECT_GT(expectRatio(survey, k, [&](int, int) { return factor; }), 5000) << "frame " << k;
  }
}

TEST(RgbAutoGain, HoldsInsideTheDeadBandAndStepsDownWhenTooBright) {
  RgbAutoGainConfig config;
  config.enabled = true;
  config.target_dn = 100.0;
  config.step_db = 2.0;
  config.interval_s = 0.1;
  config.deadband_db = 1.0;
  config.initial_db = 4.0;
  RgbAutoGain gain(config, 20.0);  // meters every 2nd frame
  EXPECT_EQ(gain.meteringPeriodFrames(), 2);
  gain.meter(0, 300.0);  // not a metering frame
  EXPECT_EQ(gain.gainDb(), 4.0);
  gain.meter(1, 105.0);  // 0.4 dB off: inside the dead band
  EXPECT_EQ(gain.gainDb(), 4.0);
  gain.meter(3, 200.0);  // 6 dB too bright: one step down
  EXPECT_EQ(gain.gainDb(), 2.0);
  EXPECT_NEAR(gain.gain(), std::pow(10.0, 0.1), 1e-12);
  gain.meter(5, 250.0);
  gain.meter(7, 250.0);
  EXPECT_EQ(gain.gainDb(), 0.0);  // clamped at min_db
  RgbAutoGain off(RgbAutoGainConfig{}, 25.0);
  off.meter(4, 1.0);
  EXPECT_EQ(off.gain(), 1.0);
}

}  // namespace
}  // namespace hsmap
