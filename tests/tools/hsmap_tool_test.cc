// Runs the built `hsmap` executable (HSMAP_TOOL_PATH) as a user would and
// checks exit statuses, stdout and stderr.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>

#include "tests/support/pristine_sample.h"
#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::pristineSample;
using testing::quoted;
using testing::readText;
using testing::runHsmap;
using testing::RunResult;
using testing::replaceInFile;
using testing::TempFolder;
using testing::writeText;


class HsmapToolTest : public ::testing::Test {
 protected:
  TempFolder temp_{"tool"};
  std::filesystem::path survey_ = temp_ / "survey";
};

TEST_F(HsmapToolTest, VersionAndHelp) {
  const RunResult version = runHsmap(temp_, "--version");
  EXPECT_EQ(version.exit_status, 0);
  EXPECT_EQ(version.out.rfind("hsmap ", 0), 0u) << version.out;

  const RunResult help = runHsmap(temp_, "--help");
  EXPECT_EQ(help.exit_status, 0);
  EXPECT_NE(help.out.find("inspect"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("sample"), std::string::npos) << help.out;

  const RunResult sample_help = runHsmap(temp_, "sample --help");
  EXPECT_EQ(sample_help.exit_status, 0);
  EXPECT_NE(sample_help.out.find("--out"), std::string::npos) << sample_help.out;
  EXPECT_NE(sample_help.out.find("--force"), std::string::npos) << sample_help.out;

  const RunResult inspect_help = runHsmap(temp_, "inspect --help");
  EXPECT_EQ(inspect_help.exit_status, 0);
  EXPECT_NE(inspect_help.out.find("SURVEY"), std::string::npos) << inspect_help.out;
}

TEST_F(HsmapToolTest, NoSubcommandIsAUsageError) {
  const RunResult result = runHsmap(temp_, "");
  EXPECT_EQ(result.exit_status, 1);
  EXPECT_FALSE(result.err.empty());
}

TEST_F(HsmapToolTest, SampleThenInspectSucceeds) {
  const RunResult sample = runHsmap(temp_, "sample --out " + quoted(survey_.string()));
  ASSERT_EQ(sample.exit_status, 0) << sample.err;
  EXPECT_NE(sample.out.find("wrote the sample survey"), std::string::npos) << sample.out;
  EXPECT_NE(sample.out.find("75 PNG frames of 160x120"), std::string::npos) << sample.out;
  EXPECT_TRUE(std::filesystem::exists(survey_ / "survey.yaml"));

  const RunResult inspect = runHsmap(temp_, "inspect " + quoted(survey_.string()));
  EXPECT_EQ(inspect.exit_status, 0) << inspect.err;
  EXPECT_TRUE(inspect.err.empty()) << inspect.err;
  for (const char* expected :
       {"survey 'hsmap-sample'", "RGB frames: 75 frames", "UHI lines: 90 lines",
        "INS fixes: 6 fixes", "wavelengths 400.0 - 800.0 nm", "warnings: none"}) {
    EXPECT_NE(inspect.out.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                             << inspect.out;
  }
}

TEST_F(HsmapToolTest, SampleRefusesANonEmptyFolderUnlessForced) {
  writeText(survey_ / "precious.txt", "keep me");
  const RunResult refused = runHsmap(temp_, "sample --out " + quoted(survey_.string()));
  EXPECT_EQ(refused.exit_status, 1);
  EXPECT_EQ(refused.err,
            "error: " + survey_.string() +
                " is not empty; pass --force to replace it (its contents will be deleted)\n");
  EXPECT_EQ(readText(survey_ / "precious.txt"), "keep me");
  EXPECT_FALSE(std::filesystem::exists(survey_ / "survey.yaml"));

  const RunResult forced = runHsmap(temp_, "sample --force --out " + quoted(survey_.string()));
  EXPECT_EQ(forced.exit_status, 0) << forced.err;
  EXPECT_TRUE(std::filesystem::exists(survey_ / "survey.yaml"));
  EXPECT_FALSE(std::filesystem::exists(survey_ / "precious.txt"));

  // An empty folder is fine without --force.
  std::filesystem::create_directories(temp_ / "empty");
  EXPECT_EQ(runHsmap(temp_, "sample --out " + quoted((temp_ / "empty").string())).exit_status, 0);
}

// Each malformed survey: exit status 2 and exactly one error line on stderr
// that names the file and the line or key.
class HsmapInspectErrorTest : public HsmapToolTest {
 protected:
  void SetUp() override { testing::copyFolder(pristineSample(), survey_); }

  void expectInspectError(const std::string& expected_message) {
    const RunResult result = runHsmap(temp_, "inspect " + quoted(survey_.string()));
    EXPECT_EQ(result.exit_status, 2);
    EXPECT_EQ(result.err, "error: " + expected_message + "\n");
    EXPECT_TRUE(result.out.empty()) << result.out;
  }
};

TEST_F(HsmapInspectErrorTest, MissingFolder) {
  std::filesystem::remove_all(survey_);
  expectInspectError(survey_.string() +
                     ": survey folder not found (expected a folder holding survey.yaml)");
}

TEST_F(HsmapInspectErrorTest, UnknownYamlKey) {
  const auto yaml = survey_ / "survey.yaml";
  replaceInFile(yaml, "name: hsmap-sample\n", "name: hsmap-sample\nnmae: typo\n");
  const std::string text = readText(yaml);
  const auto line =
      1 + std::count(text.begin(), text.begin() + static_cast<long>(text.find("nmae")), '\n');
  expectInspectError(
      yaml.string() + ":line " + std::to_string(line) +
      ", key nmae: unknown key; expected one of: format, name, rgb, uhi, ins, origin, lights");
}

TEST_F(HsmapInspectErrorTest, NanInTheIns) {
  const auto ins = survey_ / "nav/ins.csv";
  std::string text = readText(ins);
  const auto row = text.find('\n') + 1;  // first data row, line 2
  const auto depth_start = [&] {
    std::size_t at = row;
    for (int comma = 0; comma < 3; ++comma) at = text.find(',', at) + 1;
    return at;
  }();
  text.replace(depth_start, text.find(',', depth_start) - depth_start, "NaN");
  writeText(ins, text);
  expectInspectError(ins.string() + ":line 2: column 'depth': expected a finite number, got 'NaN'");
}

TEST_F(HsmapInspectErrorTest, MissingFrameFile) {
  std::filesystem::remove(survey_ / "rgb/frame_0074.png");
  expectInspectError(
      (survey_ / "rgb/frames.csv").string() +
      ":line 76: column 'file': image 'frame_0074.png' not found (expected the file " +
      (survey_ / "rgb/frame_0074.png").string() + ")");
}

TEST_F(HsmapInspectErrorTest, LinesCsvCountDiffersFromTheCube) {
  const auto lines = survey_ / "uhi/lines.csv";
  writeText(lines, readText(lines) + "90,36003.5\n");
  expectInspectError(lines.string() + ":line 92: row for scan line 90, but the cube " +
                     (survey_ / "uhi/cube.hdr").string() +
                     " has 90 lines; expected one row per scan line (91 rows given)");
}

TEST_F(HsmapInspectErrorTest, TruncatedCubeNamesTheDataFile) {
  const auto raw = survey_ / "uhi/cube.raw";
  std::filesystem::resize_file(raw, 1000);
  const RunResult result = runHsmap(temp_, "inspect " + quoted(survey_.string()));
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(result.err.rfind("error: " + raw.string() + ":", 0), 0u) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

// `hsmap simulate`: the tiny preset end to end (it loads back through
// `hsmap inspect` with its truth folder), and the command's usage errors.
TEST_F(HsmapToolTest, SimulateTinyThenInspectSeesTheTruth) {
  const RunResult simulate =
      runHsmap(temp_, "simulate --preset tiny --out " + quoted(survey_.string()));
  ASSERT_EQ(simulate.exit_status, 0) << simulate.err;
  for (const char* expected : {"simulated survey written to", "rgb frames:", "uhi lines:",
                               "truth: reflectance", "peak memory"}) {
    EXPECT_NE(simulate.out.find(expected), std::string::npos) << "missing '" << expected
                                                              << "' in\n" << simulate.out;
  }
  EXPECT_FALSE(std::filesystem::exists(survey_.string() + ".partial"));
  const RunResult inspect = runHsmap(temp_, "inspect " + quoted(survey_.string()));
  EXPECT_EQ(inspect.exit_status, 0) << inspect.err;
  EXPECT_NE(inspect.out.find("survey 'tiny'"), std::string::npos) << inspect.out;
  EXPECT_NE(inspect.out.find("truth"), std::string::npos) << inspect.out;
}

// `hsmap run --until frontend` on the tiny simulated survey, through the real
// binary: every frame posed, the front-end's files written, a summary.
TEST_F(HsmapToolTest, RunFrontendOnTinyPosesEveryFrame) {
  const RunResult simulate =
      runHsmap(temp_, "simulate --preset tiny --out " + quoted(survey_.string()));
  ASSERT_EQ(simulate.exit_status, 0) << simulate.err;
  const auto run_folder = temp_ / "run";
  const RunResult run = runHsmap(temp_, "run " + quoted(survey_.string()) + " --out " +
                                            quoted(run_folder.string()) + " --until frontend");
  ASSERT_EQ(run.exit_status, 0) << run.err << run.out;
  EXPECT_TRUE(run.err.empty()) << run.err;
  const std::string frames = std::to_string(testing::countLines(survey_ / "rgb/frames.csv") - 1);
  EXPECT_NE(run.out.find("front-end: " + frames + " of " + frames + " frames posed"),
            std::string::npos)
      << run.out;
  for (const char* expected : {"frontend: ", "frames/s", "stage times and peak memory", "total "}) {
    EXPECT_NE(run.out.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                         << run.out;
  }
  for (const char* file : {"keyframes.csv", "observations.csv", "landmarks.csv", "frames.csv",
                           "frame_stats.csv", "losses.csv", "frames.tum"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(run_folder / "frontend" / file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(run_folder / "frontend.partial"));
  // One TUM line per posed frame.
  EXPECT_EQ(std::to_string(testing::countLines(run_folder / "frontend/frames.tum")), frames);

  // A second run into the same folder finds the stage up to date and says
  // so; --force runs it again; an unknown stage or value is a usage error.
  const std::string again_arguments =
      "run " + quoted(survey_.string()) + " --out " + quoted(run_folder.string()) + " --until frontend";
  const auto keyframes_time = std::filesystem::last_write_time(run_folder / "frontend/keyframes.csv");
  const RunResult again = runHsmap(temp_, again_arguments);
  EXPECT_EQ(again.exit_status, 0) << again.err;
  EXPECT_NE(again.out.find("stage frontend: up to date, skipped"), std::string::npos) << again.out;
  EXPECT_EQ(std::filesystem::last_write_time(run_folder / "frontend/keyframes.csv"), keyframes_time);
  const RunResult forced = runHsmap(temp_, again_arguments + " --force");
  EXPECT_EQ(forced.exit_status, 0) << forced.err;
  EXPECT_EQ(forced.out.find("up to date"), std::string::npos) << forced.out;
  EXPECT_NE(forced.out.find("front-end: " + frames + " of " + frames + " frames posed"), std::string::npos)
      << forced.out;
  const RunResult unknown = runHsmap(temp_, "run " + quoted(survey_.string()) + " --out " +
                                                quoted(run_folder.string()) + " --until mesh");
  EXPECT_EQ(unknown.exit_status, 1);
  EXPECT_EQ(unknown.err,
            "error: unknown stage 'mesh' for --until; the sequential variant runs frontend, georef, "
            "surface, refine, radiometry, products\n");
  const RunResult surface = runHsmap(temp_, "run " + quoted(survey_.string()) + " --out " +
                                                quoted(run_folder.string()) + " --surface poisson");
  EXPECT_EQ(surface.exit_status, 1);
  EXPECT_EQ(surface.err, "error: --surface: expected dense or sparse, got 'poisson'\n");
  const RunResult cell = runHsmap(temp_, "run " + quoted(survey_.string()) + " --out " +
                                             quoted(run_folder.string()) + " --point-cell 0");
  EXPECT_EQ(cell.exit_status, 1);
  EXPECT_EQ(cell.err,
            "error: --point-cell: expected a cell size between 0.001 and 10 m (default 0.02; --no-points "
            "skips the point cloud), got 0\n");
}

TEST_F(HsmapToolTest, SimulateUsageErrors) {
  const RunResult presets = runHsmap(temp_, "simulate --list-presets");
  EXPECT_EQ(presets.exit_status, 0);
  EXPECT_EQ(presets.out, "tiny\nflat\nlow-relief\nrugged\ntransect-100m\n");

  const RunResult unknown = runHsmap(temp_, "simulate --preset huge --out " + quoted(survey_.string()));
  EXPECT_EQ(unknown.exit_status, 1);
  EXPECT_EQ(unknown.err,
            "error: unknown preset 'huge'; expected one of tiny, flat, low-relief, rugged, "
            "transect-100m\n");

  const RunResult no_out = runHsmap(temp_, "simulate --preset tiny");
  EXPECT_EQ(no_out.exit_status, 1);
  EXPECT_EQ(no_out.err, "error: --out is required\n");

  const RunResult neither = runHsmap(temp_, "simulate --out " + quoted(survey_.string()));
  EXPECT_EQ(neither.exit_status, 1);
  EXPECT_NE(neither.err.find("give --preset NAME or --config FILE.yaml"), std::string::npos);

  writeText(temp_ / "bad.yaml", "format: hsmap-simulation/1\npreset: tiny\nseed: -3\n");
  const RunResult bad = runHsmap(
      temp_, "simulate --config " + quoted((temp_ / "bad.yaml").string()) + " --out " +
                 quoted(survey_.string()));
  EXPECT_EQ(bad.exit_status, 2);
  EXPECT_EQ(bad.err, "error: " + (temp_ / "bad.yaml").string() +
                         ":line 3, key seed: expected an integer in [0, 9e15], got -3\n");
  EXPECT_FALSE(std::filesystem::exists(survey_));
}

}  // namespace
}  // namespace hsmap
