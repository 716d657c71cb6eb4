// A stage's fingerprint depends on its own options and inputs, not on the
// variant that runs it (pipelines/run/stage_fingerprints.h): sequential and
// joint give frontend, georef and surface the same fingerprints, so the
// stage folders of one are up to date in the other's run folder (what
// `hsmap compare` relies on; CompareCommand checks that joint then skips
// them), and a joint run stopped before its joint stage still publishes a
// calibration.yaml that evaluate accepts as joint's.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

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

// The `fingerprint: "..."` of RUN/stages/<stage>.yaml.
std::string fingerprintOf(const fs::path& run, const std::string& stage) {
  const std::string text = readText(run / "stages" / (stage + ".yaml"));
  const std::string key = "fingerprint: \"";
  const std::size_t start = text.find(key);
  if (start == std::string::npos) return "(none in " + stage + ".yaml)";
  return text.substr(start + key.size(), 16);
}

class SharedStages : public ::testing::Test {
 protected:
  TempFolder temp_{"shared-stages"};

  RunResult run(const fs::path& out, const std::string& extra) {
    return runHsmap(temp_, "run " + quoted(testing::simulatedTinySurvey().string()) + " --out " +
                               quoted(out.string()) + " --threads 1 " + extra);
  }
};

TEST_F(SharedStages, SequentialAndJointGiveTheirCommonStagesTheSameFingerprints) {
  const fs::path sequential = temp_ / "sequential", joint = temp_ / "joint";
  const RunResult first = run(sequential, "--until surface");
  ASSERT_EQ(first.exit_status, 0) << first.err << first.out;
  const RunResult second = run(joint, "--variant joint --until surface");
  ASSERT_EQ(second.exit_status, 0) << second.err << second.out;
  for (const char* stage : {"frontend", "georef", "surface"}) {
    EXPECT_EQ(fingerprintOf(sequential, stage), fingerprintOf(joint, stage)) << stage;
  }
  // The contract's calibration.yaml names the run's variant, georef's own
  // file the method that made it.
  EXPECT_NE(readText(joint / "calibration.yaml").find("variant: joint\n"), std::string::npos);
  EXPECT_NE(readText(joint / "georef/calibration.yaml").find("variant: sequential\n"), std::string::npos);
  const RunResult evaluated =
      runHsmap(temp_, "evaluate " + quoted(joint.string()) + " --truth " +
                          quoted((testing::simulatedTinySurvey() / "truth").string()));
  EXPECT_EQ(evaluated.exit_status, 0) << evaluated.err;

  // A planar georef is another computation (the INS alone): never shared.
  const fs::path planar = temp_ / "planar";
  const RunResult third = run(planar, "--variant planar --until georef");
  ASSERT_EQ(third.exit_status, 0) << third.err << third.out;
  EXPECT_NE(fingerprintOf(planar, "georef"), fingerprintOf(sequential, "georef"));
}

}  // namespace
}  // namespace hsmap
