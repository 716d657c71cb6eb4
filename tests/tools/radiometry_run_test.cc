// The radiometry stage end to end on the simulated `tiny` survey (which has
// `lights`), through the real binary: the water estimate and the reflectance
// product are written on the radiance ortho's grid, `hsmap evaluate` scores
// them, and the reflectance's spectra are closer to the truth than the
// radiance's; a survey without `lights` gets radiance only and says why.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/io/envi_reader.h"
#include "core/survey/run_calibration.h"
#include "core/survey/water_estimate.h"
#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"
#include "tests/tools/simulated_tiny_survey.h"

namespace hsmap {
namespace {

using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runHsmap;
using testing::TempFolder;

namespace fs = std::filesystem;

// A number of metrics.json by key; NaN when missing or null.
double metric(const std::string& json, const std::string& key) {
  const std::regex pattern("\"" + key + "\"\\s*:\\s*(null|[-0-9.eE+]+)");
  std::smatch match;
  if (!std::regex_search(json, match, pattern) || match[1] == "null") return std::nan("");
  return std::stod(match[1]);
}

TEST(RadiometryRun, WritesReflectanceThatEvaluateScoresBetterThanRadiance) {
  const TempFolder temp("radiometry-run");
  const fs::path survey = testing::simulatedTinySurvey();
  const fs::path out = temp / "run";
  const RunResult run = runHsmap(temp, "run " + quoted(survey.string()) + " --out " + quoted(out.string()));
  ASSERT_EQ(run.exit_status, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("stage radiometry"), std::string::npos) << run.out;

  const WaterEstimate water = readWaterEstimate(out / "radiometry/water.yaml");
  const EnviReader ortho(out / "hyperspectral/ortho.hdr");
  const EnviReader reflectance(out / "hyperspectral/reflectance.hdr");
  ASSERT_EQ(water.bands(), ortho.bands());
  for (std::size_t b = 0; b < water.attenuation_per_m.size(); ++b) {
    EXPECT_GE(water.attenuation_per_m[b], 0.0) << b;
    EXPECT_TRUE(water.attenuation_sigma_per_m[b].has_value()) << b;
  }
  // calibration.yaml carries the contract's water block.
  const RunCalibration calibration = readRunCalibration(out / "calibration.yaml");
  ASSERT_TRUE(calibration.water.has_value());
  EXPECT_EQ(calibration.water->attenuation_per_m, water.attenuation_per_m);
  // The same grid, map info and bands as the radiance ortho.
  EXPECT_EQ(reflectance.samples(), ortho.samples());
  EXPECT_EQ(reflectance.lines(), ortho.lines());
  EXPECT_EQ(reflectance.bands(), ortho.bands());
  ASSERT_TRUE(reflectance.header().map_info.has_value());
  EXPECT_EQ(*reflectance.header().map_info, *ortho.header().map_info);
  EXPECT_EQ(reflectance.header().wavelength, ortho.header().wavelength);
  EXPECT_TRUE(fs::exists(out / "hyperspectral/reflectance.tif"));
  // The log counts the NaN pixels by cause.
  EXPECT_TRUE(std::regex_search(run.out, std::regex("reflectance: [0-9]+ of [0-9]+ pixels \\([0-9]+ empty in the "
                                                    "radiance ortho, [0-9]+ NaN in a lamp's shadow, [0-9]+ NaN "
                                                    "undetermined")))
      << run.out;
  // tiny is one lane at a nearly constant altitude over low relief: the
  // stage must say that it cannot pin c(λ) down.
  EXPECT_NE(run.out.find("does not determine c(λ)"), std::string::npos) << run.out;

  const RunResult evaluate =
      runHsmap(temp, "evaluate " + quoted(out.string()) + " --truth " + quoted((survey / "truth").string()));
  ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err << evaluate.out;
  const std::string json = readText(out / "metrics.json");
  for (const char* key : {"reflectance_sam_deg", "reflectance_rmse", "reflectance_gain_free_rmse",
                          "water_attenuation_rmse_per_m", "ortho_sam_deg"}) {
    EXPECT_TRUE(std::isfinite(metric(json, key))) << key << " in\n" << json;
  }
  // Correcting the lamps, the beam and the water must bring the spectra
  // closer to the true reflectance than the radiance is.
  EXPECT_LT(metric(json, "reflectance_sam_deg"), metric(json, "ortho_sam_deg")) << json;
}

TEST(RadiometryRun, ASurveyWithoutLightsGetsRadianceOnlyAndSaysWhy) {
  const TempFolder temp("radiometry-no-lights");
  const fs::path survey = temp / "survey";
  fs::copy(testing::simulatedTinySurvey(), survey, fs::copy_options::recursive);
  // survey.yaml without its `lights` block (the block runs to the end of the file or the next top-level key).
  std::ifstream in(survey / "survey.yaml");
  std::ostringstream kept;
  bool in_lights = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("lights:", 0) == 0) {
      in_lights = true;
      continue;
    }
    if (in_lights && !line.empty() && line[0] != ' ') in_lights = false;
    if (!in_lights) kept << line << "\n";
  }
  in.close();
  std::ofstream(survey / "survey.yaml") << kept.str();
  const fs::path out = temp / "run";
  const RunResult run = runHsmap(temp, "run " + quoted(survey.string()) + " --out " + quoted(out.string()));
  ASSERT_EQ(run.exit_status, 0) << run.err << run.out;
  EXPECT_NE(run.out.find("no `lights` block"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(out / "hyperspectral/ortho.hdr"));
  EXPECT_FALSE(fs::exists(out / "hyperspectral/reflectance.hdr"));
  EXPECT_FALSE(fs::exists(out / "radiometry/water.yaml"));
}

}  // namespace
}  // namespace hsmap
