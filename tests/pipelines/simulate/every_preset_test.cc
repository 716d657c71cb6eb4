// Every preset simulates and loads back through the survey loader. The
// presets' full sizes take minutes (benchmarks/simulate_benchmark.sh); here
// each keeps its scene, motion, optics and calibration but flies 1.5 m with
// small images, which exercises the same code paths.
#include <gtest/gtest.h>

#include <sstream>

#include "core/survey/survey.h"
#include "core/survey/survey_truth.h"
#include "pipelines/simulate/simulate_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

class EveryPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryPreset, SimulatesAndLoadsBackWithItsTruth) {
  SimulationConfig config = *simulationPreset(GetParam());
  config.motion.length_m = 1.5;
  config.rgb.camera = scaledRgbCamera(160, 90);
  config.uhi.camera = scaledUhiCamera(120);
  config.uhi.bands = 12;
  testing::TempFolder temp("preset");
  std::ostringstream log;
  const SimulationSummary summary = simulateSurvey(config, temp / "survey", log);
  const Survey survey = loadSurvey(temp / "survey");
  EXPECT_EQ(survey.config.name, GetParam());
  EXPECT_EQ(survey.rgb.frameCount(), summary.rgb_frames);
  EXPECT_GT(summary.rgb_frames, 50);
  EXPECT_EQ(survey.cube->lines(), summary.uhi_lines);
  EXPECT_EQ(survey.cube->bands(), 12);
  EXPECT_EQ(survey.wavelengths_nm.front(), 400.0);
  EXPECT_EQ(survey.wavelengths_nm.back(), 800.0);
  EXPECT_TRUE(survey.truth.present);
  const SurveyTruth truth = loadSurveyTruth(temp / "survey");
  EXPECT_EQ(truth.uhi_poses.size(), std::size_t(summary.uhi_lines));
  EXPECT_GT(summary.reflectance_valid_pixels, 10000);
}

INSTANTIATE_TEST_SUITE_P(Presets, EveryPreset,
                         ::testing::ValuesIn(simulationPresetNames()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) c = (c == '-') ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace hsmap
