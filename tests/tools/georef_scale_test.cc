// The map's scale from the INS, stated and checked: on three seeds of the
// simulated `tiny` survey, `hsmap run --until georef` writes
// georef/map_placement.yaml with the 1-sigma of the map's scale, and the
// scale error `hsmap evaluate` measures against the truth lies within 3 of
// those sigmas (docs/GEOREF.md, "The map's scale and placement").
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runHsmap;
using testing::TempFolder;

namespace fs = std::filesystem;

// `key: number` in a YAML or `"key": number` in a JSON text; NaN when absent.
double numberAfter(const std::string& text, const std::string& key) {
  const std::regex pattern("\"?" + key + "\"?\\s*:\\s*([-0-9.eE+]+)");
  std::smatch match;
  if (!std::regex_search(text, match, pattern)) return std::nan("");
  return std::stod(match[1]);
}

TEST(GeorefScale, TheStatedScaleSigmaCoversTheScaleErrorOnThreeSeeds) {
  const TempFolder temp("georef-scale");
  for (int seed : {1, 2, 3}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const fs::path config = temp / ("tiny-" + std::to_string(seed) + ".yaml");
    std::ofstream(config) << "format: hsmap-simulation/1\npreset: tiny\nseed: " << seed << "\n";
    const fs::path survey = temp / ("survey-" + std::to_string(seed));
    const fs::path out = temp / ("run-" + std::to_string(seed));
    const RunResult simulate =
        runHsmap(temp, "simulate --config " + quoted(config.string()) + " --out " + quoted(survey.string()));
    ASSERT_EQ(simulate.exit_status, 0) << simulate.err;
    const RunResult run = runHsmap(temp, "run " + quoted(survey.string()) + " --out " +
                                             quoted(out.string()) + " --until georef");
    ASSERT_EQ(run.exit_status, 0) << run.err << run.out;
    const RunResult evaluate = runHsmap(temp, "evaluate " + quoted(out.string()) + " --truth " +
                                                  quoted((survey / "truth").string()));
    ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err << evaluate.out;

    const std::string placement = readText(out / "georef" / "map_placement.yaml");
    const double sigma = numberAfter(placement, "scale_sigma");
    const std::string metrics = readText(out / "metrics.json");
    const double error = numberAfter(metrics, "rgb_scale_error");
    ASSERT_TRUE(std::isfinite(sigma) && std::isfinite(error))
        << placement << metrics;
    EXPECT_GT(sigma, 0.0);
    EXPECT_LE(error, 3.0 * sigma) << "scale error " << error << ", stated 1-sigma " << sigma;
  }
}

}  // namespace
}  // namespace hsmap
