// `hsmap compare` through the real binary on the tiny survey
// (pipelines/compare/compare_runner.h, docs/COMPARE.md): the four variants
// run, the front-end once (joint takes sequential's frontend, georef and
// surface, hard-linked, and skips them), each evaluated, the three tables
// written with a row of figures per metric from each run's metrics.json; a
// variant that fails is a column saying why while the others run; usage
// mistakes are exact errors.

#include <sys/stat.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "pipelines/compare/compare_csv.h"
#include "pipelines/compare/metrics_file.h"
#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"
#include "tests/tools/simulated_tiny_survey.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;
using testing::quoted;
using testing::readText;
using testing::RunResult;
using testing::runHsmap;
using testing::TempFolder;

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

ino_t inodeOf(const fs::path& file) {
  struct stat status {};
  return ::stat(file.c_str(), &status) == 0 ? status.st_ino : 0;
}

class CompareCommand : public ::testing::Test {
 protected:
  TempFolder temp_{"compare-command"};

  RunResult compare(const fs::path& out, const std::string& extra) {
    return runHsmap(temp_, "compare " + quoted(testing::simulatedTinySurvey().string()) + " --out " +
                               quoted(out.string()) + " --threads 1 " + extra,
                    300);
  }
};

TEST_F(CompareCommand, RunsEveryVariantWithTheFrontEndOnceAndTabulatesTheirMetrics) {
  const fs::path out = temp_ / "compare";
  const RunResult result = compare(out, "");
  ASSERT_EQ(result.exit_status, 0) << result.err << result.out;

  // The front-end ran once, in sequential; joint skipped the three stages it took.
  EXPECT_EQ(count(result.out, "| stage frontend\n"), 1u) << result.out;
  EXPECT_NE(result.out.find("compare: joint takes frontend, georef, surface from sequential"), std::string::npos);
  const std::string joint_log = readText(out / "joint.log");
  for (const char* stage : {"frontend", "georef", "surface"}) {
    EXPECT_NE(joint_log.find("stage " + std::string(stage) + ": up to date, skipped"), std::string::npos) << stage;
  }
  EXPECT_EQ(joint_log.find("stage frontend\n"), std::string::npos);
  EXPECT_EQ(inodeOf(out / "joint/surface/mesh.ply"), inodeOf(out / "sequential/surface/mesh.ply"));
  EXPECT_EQ(readText(out / "joint/stages/frontend.yaml"), readText(out / "sequential/stages/frontend.yaml"));

  // Four columns, each ok, each metric as its run's metrics.json says.
  const CompareTable table = readCompareCsv(out / "compare.csv");
  ASSERT_EQ(table.variants.size(), 4u);
  const char* names[] = {"stacked", "planar", "sequential", "joint"};
  for (std::size_t c = 0; c < 4; ++c) {
    EXPECT_EQ(table.variants[c].variant, names[c]);
    EXPECT_EQ(table.variants[c].status, "ok") << names[c];
    EXPECT_GT(table.variants[c].wall_time_s, 0.0) << names[c];
    const MetricFigures metrics = readMetricsFile(out / names[c] / "metrics.json");
    for (const auto& [key, value] : metrics) {
      const auto row = std::find_if(table.metric_rows.begin(), table.metric_rows.end(),
                                    [&](const CompareRow& r) { return r.key == key; });
      ASSERT_NE(row, table.metric_rows.end()) << key;
      EXPECT_EQ(row->values[c], value) << names[c] << " " << key;
    }
  }
  EXPECT_EQ(table.variants[3].shared_stages, (std::vector<std::string>{"frontend", "georef", "surface"}));
  EXPECT_EQ(table.variants[3].shared_from, "sequential");
  const std::string html = readText(out / "compare.html");
  EXPECT_EQ(count(html, "<img src=\"data:image/png;base64,"), 4u);
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_NE(readText(out / "compare.md").find("| `rgb_ate_m` | lower |"), std::string::npos);
  EXPECT_NE(result.out.find("compare: wrote " + (out / "compare.csv").string()), std::string::npos);

  // Again on the same folder: every run resumes, nothing runs again.
  const RunResult again = compare(out, "--variants sequential,joint");
  ASSERT_EQ(again.exit_status, 0) << again.err << again.out;
  EXPECT_EQ(count(again.out, "| stage frontend\n"), 0u) << again.out;
  EXPECT_EQ(readCompareCsv(out / "compare.csv").variants.size(), 2u);
}

TEST_F(CompareCommand, AVariantThatFailsIsAColumnSayingWhyAndTheOthersStillRun) {
  const fs::path out = temp_ / "compare";
  fs::create_directories(out);
  std::ofstream(out / "planar") << "not a run folder\n";
  const RunResult result = compare(out, "--variants planar,stacked");
  EXPECT_EQ(result.exit_status, 1) << result.err << result.out;
  const CompareTable table = readCompareCsv(out / "compare.csv");
  ASSERT_EQ(table.variants.size(), 2u);
  EXPECT_EQ(table.variants[0].status, "failed: " + (out / "planar").string() + " exists and is not a folder");
  EXPECT_EQ(table.variants[1].status, "ok");
  EXPECT_NE(result.err.find("error: 1 of 2 variants failed"), std::string::npos) << result.err;
}

TEST_F(CompareCommand, UsageMistakesAreExactErrors) {
  const RunResult unknown = compare(temp_ / "a", "--variants planar,fused");
  EXPECT_EQ(unknown.exit_status, 1);
  EXPECT_EQ(unknown.err,
            "error: --variants: unknown variant 'fused' in 'planar,fused'; expected names among stacked, planar, "
            "sequential, joint, separated by commas\n");
  const RunResult twice = compare(temp_ / "a", "--variants joint,joint");
  EXPECT_EQ(twice.err, "error: --variants: 'joint' is listed twice in 'joint,joint'\n");

  const fs::path survey = testing::simulatedTinySurvey();
  const RunResult inside = compare(survey / "runs", "--variants stacked");
  EXPECT_EQ(inside.exit_status, 1);
  EXPECT_EQ(inside.err, "error: --out " + (survey / "runs").string() + " lies inside the survey folder " +
                            survey.string() +
                            ": the variants' runs would change the survey's files as each other sees them; "
                            "choose a folder outside it\n");
  const RunResult missing = runHsmap(temp_, "compare " + quoted((temp_ / "nowhere").string()) + " --out " +
                                                quoted((temp_ / "b").string()));
  EXPECT_EQ(missing.exit_status, 2) << missing.err;
  EXPECT_EQ(missing.err.rfind("error: " + (temp_ / "nowhere/survey.yaml").string(), 0), 0u) << missing.err;
}

}  // namespace
}  // namespace hsmap
