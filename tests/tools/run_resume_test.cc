// The stage runner through the real binary on the tiny survey
// (pipelines/run/runner.h, docs/RUN.md): `--from` any stage reproduces a
// full run's products byte for byte, a second run skips every stage and says
// so, a changed option redoes its stage and the ones after, a run killed with
// SIGKILL during products resumes to the same products, and an option the
// variant ignores is an error naming both.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"
#include "tests/tools/simulated_tiny_survey.h"

namespace hsmap {
namespace {

namespace fs = std::filesystem;
using testing::quoted;
using testing::RunResult;
using testing::runHsmap;
using testing::TempFolder;

const fs::path& tinySurvey() { return testing::simulatedTinySurvey(); }

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The run's products (the contract's files and the products stage's): path
// relative to RUN -> content.
std::map<std::string, std::string> products(const fs::path& run) {
  std::map<std::string, std::string> files;
  for (const char* folder : {"trajectory", "map", "hyperspectral"}) {
    if (!fs::exists(run / folder)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(run / folder)) {
      if (entry.is_regular_file()) {
        files[entry.path().lexically_relative(run).generic_string()] = bytesOf(entry.path());
      }
    }
  }
  if (fs::exists(run / "calibration.yaml")) files["calibration.yaml"] = bytesOf(run / "calibration.yaml");
  return files;
}

// Names of the files whose bytes differ (or that only one side has).
std::vector<std::string> differing(const std::map<std::string, std::string>& a,
                                   const std::map<std::string, std::string>& b) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : a) {
    const auto other = b.find(name);
    if (other == b.end() || other->second != bytes) names.push_back(name);
  }
  for (const auto& [name, bytes] : b) {
    if (!a.contains(name)) names.push_back(name + " (only in the second)");
  }
  return names;
}

class RunResume : public ::testing::Test {
 protected:
  TempFolder temp_{"run-resume"};

  RunResult run(const fs::path& out, const std::string& extra) {
    return runHsmap(temp_, "run " + quoted(tinySurvey().string()) + " --out " + quoted(out.string()) +
                               " --threads 1 " + extra);
  }
};

// Every stage of every variant started with --from on a finished run gives
// the full run's products, byte for byte.
TEST_F(RunResume, FromEachStageReproducesTheFullRunsProducts) {
  const std::map<std::string, std::vector<std::string>> variants = {
      {"sequential", {"frontend", "georef", "surface", "refine", "radiometry", "products"}},
      {"joint", {"frontend", "georef", "surface", "joint", "radiometry", "products"}},
      {"planar", {"georef", "surface", "radiometry", "products"}},
      {"stacked", {"products"}}};
  for (const auto& [variant, stages] : variants) {
    const fs::path out = temp_ / variant;
    const RunResult full = run(out, "--variant " + variant);
    ASSERT_EQ(full.exit_status, 0) << full.err << full.out;
    const auto expected = products(out);
    ASSERT_GE(expected.size(), variant == "stacked" ? 5u : 15u) << variant;
    for (const std::string& stage : stages) {
      const RunResult again = run(out, "--variant " + variant + " --from " + stage);
      ASSERT_EQ(again.exit_status, 0) << variant << " --from " << stage << "\n" << again.err << again.out;
      EXPECT_NE(again.out.find("stage " + stage + "\n"), std::string::npos) << again.out;
      EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{})
          << variant << " --from " << stage;
    }
  }
}

TEST_F(RunResume, ASecondRunSkipsEveryStageAndAChangedOptionRedoesItsStageAndTheOnesAfter) {
  const fs::path out = temp_ / "sequential";
  const RunResult full = run(out, "");
  ASSERT_EQ(full.exit_status, 0) << full.err << full.out;
  const auto expected = products(out);
  const auto ortho_time = fs::last_write_time(out / "hyperspectral/ortho.raw");

  const RunResult again = run(out, "");
  ASSERT_EQ(again.exit_status, 0) << again.err << again.out;
  for (const char* stage : {"frontend", "georef", "surface", "refine", "radiometry", "products"}) {
    EXPECT_NE(again.out.find("stage " + std::string(stage) + ": up to date, skipped"), std::string::npos)
        << stage << "\n" << again.out;
  }
  EXPECT_EQ(fs::last_write_time(out / "hyperspectral/ortho.raw"), ortho_time);  // not rewritten
  EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{});
  EXPECT_TRUE(fs::is_regular_file(out / "run.yaml"));

  // Stopping earlier on a finished run changes nothing: the later stages are
  // still up to date, so their files stay and stay published.
  const RunResult earlier = run(out, "--until georef");
  ASSERT_EQ(earlier.exit_status, 0) << earlier.err << earlier.out;
  EXPECT_NE(earlier.out.find("stage georef: up to date, skipped"), std::string::npos) << earlier.out;
  EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{});

  // A products option: the estimation is kept, the products are made again.
  const RunResult coarser = run(out, "--ortho-pixel 0.01");
  ASSERT_EQ(coarser.exit_status, 0) << coarser.err << coarser.out;
  EXPECT_NE(coarser.out.find("stage refine: up to date, skipped"), std::string::npos) << coarser.out;
  EXPECT_NE(coarser.out.find("stage products: runs again: its options changed"), std::string::npos)
      << coarser.out;
  EXPECT_EQ(products(out).at("trajectory/uhi_lines.csv"), expected.at("trajectory/uhi_lines.csv"));
  EXPECT_NE(products(out).at("hyperspectral/ortho.hdr"), expected.at("hyperspectral/ortho.hdr"));

  // A refine option redoes refine and products; back to the first options,
  // the first products again.
  const RunResult fewer = run(out, "--extrinsic-rounds 1");
  ASSERT_EQ(fewer.exit_status, 0) << fewer.err << fewer.out;
  EXPECT_NE(fewer.out.find("stage surface: up to date, skipped"), std::string::npos) << fewer.out;
  EXPECT_NE(fewer.out.find("stage refine: runs again"), std::string::npos) << fewer.out;
  EXPECT_NE(fewer.out.find("stage products\n"), std::string::npos) << fewer.out;
  const RunResult back = run(out, "");
  ASSERT_EQ(back.exit_status, 0) << back.err << back.out;
  EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{});

  // --force redoes every stage, to the same products.
  const RunResult forced = run(out, "--force");
  ASSERT_EQ(forced.exit_status, 0) << forced.err << forced.out;
  EXPECT_EQ(forced.out.find("up to date"), std::string::npos) << forced.out;
  EXPECT_NE(forced.out.find("stage frontend\n"), std::string::npos) << forced.out;
  EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{});
}

// SIGKILL while the products stage writes: no run.yaml, no record of
// products; the next run redoes products alone, to the same bytes.
TEST_F(RunResume, ARunKilledDuringProductsResumesToTheSameProducts) {
  const fs::path reference = temp_ / "reference";
  ASSERT_EQ(run(reference, "--ortho-pixel 0.001").exit_status, 0);
  const auto expected = products(reference);

  const fs::path out = temp_ / "killed";
  const std::string command = quoted(HSMAP_TOOL_PATH) + " run " + quoted(tinySurvey().string()) + " --out " +
                              quoted(out.string()) + " --threads 1 --ortho-pixel 0.001 > " +
                              quoted((temp_ / "killed.log").string()) + " 2>&1 & echo $! > " +
                              quoted((temp_ / "pid").string());
  ASSERT_EQ(std::system(command.c_str()), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  bool in_products = false;
  while (std::chrono::steady_clock::now() < deadline) {
    // The products stage has started writing its ortho-image.
    if (fs::exists(out / "hyperspectral")) {
      in_products = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(in_products) << testing::readText(temp_ / "killed.log");
  const std::string pid = testing::readText(temp_ / "pid");
  ASSERT_EQ(std::system(("kill -KILL " + pid).c_str()), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ASSERT_FALSE(fs::exists(out / "stages/products.yaml")) << "the kill came after products ended";
  EXPECT_FALSE(fs::exists(out / "run.yaml"));

  const RunResult resumed = run(out, "--ortho-pixel 0.001");
  ASSERT_EQ(resumed.exit_status, 0) << resumed.err << resumed.out;
  EXPECT_NE(resumed.out.find("stage refine: up to date, skipped"), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("stage products\n"), std::string::npos) << resumed.out;
  EXPECT_EQ(differing(expected, products(out)), std::vector<std::string>{});
  for (const auto& entry : fs::recursive_directory_iterator(out)) {
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
  }
}

TEST_F(RunResume, UsageErrorsNameTheOptionTheStageAndTheVariant) {
  const fs::path out = temp_ / "out";
  const RunResult ignored = run(out, "--variant joint --extrinsic-rounds 1");
  EXPECT_EQ(ignored.exit_status, 1);
  EXPECT_EQ(ignored.err,
            "error: --extrinsic-rounds sets the refine stage, which the joint variant does not run; it "
            "applies to: sequential\n");
  const RunResult stacked = run(out, "--variant stacked --ortho-pixel 0.01");
  EXPECT_EQ(stacked.exit_status, 1);
  EXPECT_EQ(stacked.err,
            "error: --ortho-pixel sets the products stage, which the stacked variant runs without it; it "
            "applies to: sequential, planar, joint\n");
  const RunResult geotiff = run(out, "--variant stacked --no-geotiff");
  EXPECT_EQ(geotiff.exit_status, 1);
  EXPECT_EQ(geotiff.err,
            "error: --no-geotiff sets the products stage, which the stacked variant runs without it; it "
            "applies to: sequential, planar, joint\n");
  const RunResult depth = run(out, "--seabed-depth 3");
  EXPECT_EQ(depth.exit_status, 1);
  EXPECT_EQ(depth.err,
            "error: --seabed-depth sets the surface stage, which the sequential variant runs without it; it "
            "applies to: planar\n");
  const RunResult variant = run(out, "--variant fused");
  EXPECT_EQ(variant.exit_status, 1);
  EXPECT_EQ(variant.err, "error: --variant: expected one of sequential, planar, stacked, joint, got 'fused'\n");
  const RunResult threads =
      runHsmap(temp_, "run " + quoted(tinySurvey().string()) + " --out " + quoted(out.string()) + " --threads=-2");
  EXPECT_EQ(threads.exit_status, 1);
  EXPECT_EQ(threads.err, "error: --threads: expected a thread count >= 0 (0: every hardware thread), got -2\n");
  EXPECT_FALSE(fs::exists(out));  // nothing was started

  // --from needs the stages before it finished in RUN.
  const RunResult from = run(out, "--from surface");
  EXPECT_EQ(from.exit_status, 1);
  EXPECT_NE(from.err.find("error: --from surface starts from the files of the stages before it, but stage "
                          "frontend in " +
                          out.string() + " is not up to date: no record "),
            std::string::npos)
      << from.err;

  // Another survey's run folder is replaced only with --force.
  ASSERT_EQ(run(out, "--until frontend").exit_status, 0);
  const fs::path other = temp_ / "other-survey";
  testing::copyFolder(tinySurvey(), other);
  const RunResult foreign =
      runHsmap(temp_, "run " + quoted(other.string()) + " --out " + quoted(out.string()) + " --until frontend");
  EXPECT_EQ(foreign.exit_status, 1);
  EXPECT_NE(foreign.err.find(" holds a run of the survey " + fs::absolute(tinySurvey()).lexically_normal().string()),
            std::string::npos)
      << foreign.err;
}

TEST_F(RunResume, LogFileHoldsWhatTheTerminalShowed) {
  const fs::path out = temp_ / "out";
  const fs::path log = temp_ / "run.log";
  const RunResult result = run(out, "--until frontend --log " + quoted(log.string()));
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const std::string logged = testing::readText(log);
  EXPECT_NE(logged.find("stage frontend\n"), std::string::npos) << logged;
  EXPECT_NE(logged.find("run.yaml written"), std::string::npos) << logged;
  EXPECT_NE(result.out.find("run.yaml written"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace hsmap
