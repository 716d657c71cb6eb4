// `hsmap evaluate` as a user runs it: metrics.json and the table on success,
// exit status 2 and one line on stderr for bad input.
#include <gtest/gtest.h>

#include "tests/pipelines/evaluate/evaluation_fixture.h"
#include "tests/support/run_hsmap.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;
using testing::quoted;
using testing::readText;
using testing::runHsmap;
using testing::RunResult;
using testing::TempFolder;

class EvaluateCommandTest : public ::testing::Test {
 protected:
  RunResult evaluate() {
    return runHsmap(temp_, "evaluate " + quoted(fixture_.run().string()) + " --truth " +
                               quoted(fixture_.truth().string()));
  }
  EvaluationFixture fixture_;
  TempFolder temp_{"evaluate-command"};
};

TEST_F(EvaluateCommandTest, WritesMetricsJsonAndPrintsTheTable) {
  fixture_.writeRunEqualToTruth();
  const RunResult result = evaluate();
  EXPECT_EQ(result.exit_status, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << result.err;
  const std::string json = readText(fixture_.run() / "metrics.json");
  const std::string start = "{\n  \"variant\": \"sequential\",\n  \"rgb_ate_m\": 0,\n";
  EXPECT_EQ(json.substr(0, start.size()), start);
  EXPECT_NE(json.find("\"timings_s\": {\"frontend\": 12.5, \"georef\": 3.25, \"total\": 15.75},"),
            std::string::npos);
  EXPECT_NE(json.find("\"mesh_accuracy_m\": null,"), std::string::npos);
  EXPECT_NE(result.out.find("rgb_ate_m                               0             m     "),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("wrote " + (fixture_.run() / "metrics.json").string()),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(fixture_.run() / "metrics.json.partial"));
}

TEST_F(EvaluateCommandTest, BadInputExitsWithStatus2AndOneLine) {
  std::vector<LinePose> lines = fixture_.linesTrue();
  lines.pop_back();
  fixture_.writeRun(fixture_.framesTrue(), lines, fixture_.calibrationEqualToTruth());
  const RunResult result = evaluate();
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(result.err, "error: " + (fixture_.run() / "trajectory/uhi_lines.csv").string() +
                            ": holds scan lines 0 to 88, expected every scan line of " +
                            (fixture_.survey() / "uhi/lines.csv").string() +
                            ", 0 to 89: line 89 is missing\n");
  EXPECT_TRUE(result.out.empty()) << result.out;
  EXPECT_FALSE(std::filesystem::exists(fixture_.run() / "metrics.json"));
}

}  // namespace
}  // namespace hsmap
