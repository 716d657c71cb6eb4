// loadEvaluationInputs refuses rows that do not correspond, with the exact
// message the user sees: the file, the row and what was expected.
#include "pipelines/evaluate/evaluation_inputs.h"

#include <gtest/gtest.h>

#include "core/survey/number_text.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"
#include "tests/support/expect_input_error.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;
using testing::expectInputError;

class EvaluationInputsTest : public ::testing::Test {
 protected:
  void load() { loadEvaluationInputs(fixture_.run(), fixture_.truth()); }
  std::string framesRule() const {
    return "expected one row per frame of " + (fixture_.survey() / "rgb/frames.csv").string() +
           ", at its time within 1e-06 s";
  }
  std::string t(std::size_t frame) const { return formatDouble(fixture_.framesTrue()[frame].t); }

  EvaluationFixture fixture_;
};

TEST_F(EvaluationInputsTest, ConsistentInputsLoad) {
  fixture_.writeRunEqualToTruth();
  const EvaluationInputs inputs = loadEvaluationInputs(fixture_.run(), fixture_.truth() / "");
  EXPECT_EQ(inputs.frames.size(), 75u);
  EXPECT_EQ(inputs.lines.size(), 90u);
  EXPECT_EQ(inputs.run.variant, "sequential");
  EXPECT_TRUE(inputs.warnings.empty());
}

TEST_F(EvaluationInputsTest, AFrameMissingFromTheResultsIsNamed) {
  std::vector<TimedPose> frames = fixture_.framesTrue();
  frames.erase(frames.begin() + 10);
  fixture_.writeRun(frames, fixture_.linesTrue(), fixture_.calibrationEqualToTruth());
  expectInputError([&] { load(); }, fixture_.run() / "trajectory/frames.csv",
                   "line 12: t = " + t(11) + ", but frame 10 of the survey (t = " + t(10) +
                       ") has no row before it: " + framesRule());
}

TEST_F(EvaluationInputsTest, AnExtraFrameInTheResultsIsNamed) {
  std::vector<TimedPose> frames = fixture_.framesTrue();
  frames.insert(frames.begin() + 11, TimedPose{frames[10].t + 0.01, frames[10].T});
  fixture_.writeRun(frames, fixture_.linesTrue(), fixture_.calibrationEqualToTruth());
  expectInputError([&] { load(); }, fixture_.run() / "trajectory/frames.csv",
                   "line 13: t = " + formatDouble(frames[11].t) +
                       " is not the time of any frame (the next one is frame 11 of the survey "
                       "(t = " + t(11) + ")): an extra row; " + framesRule());
}

TEST_F(EvaluationInputsTest, ResultsEndingEarlyNameTheFirstFrameWithoutARow) {
  std::vector<TimedPose> frames = fixture_.framesTrue();
  frames.resize(70);
  fixture_.writeRun(frames, fixture_.linesTrue(), fixture_.calibrationEqualToTruth());
  expectInputError([&] { load(); }, fixture_.run() / "trajectory/frames.csv",
                   " 70 rows, frame 70 of the survey (t = " + t(70) +
                       ") and the 4 after it have none: " + framesRule());
}

TEST_F(EvaluationInputsTest, AScanLineMissingFromTheResultsIsNamed) {
  std::vector<LinePose> lines = fixture_.linesTrue();
  lines.pop_back();
  fixture_.writeRun(fixture_.framesTrue(), lines, fixture_.calibrationEqualToTruth());
  expectInputError([&] { load(); }, fixture_.run() / "trajectory/uhi_lines.csv",
                   " holds scan lines 0 to 88, expected every scan line of " +
                       (fixture_.survey() / "uhi/lines.csv").string() +
                       ", 0 to 89: line 89 is missing");
}

TEST_F(EvaluationInputsTest, AScanLineBeyondTheSurveyIsNamed) {
  std::vector<LinePose> lines = fixture_.linesTrue();
  lines.push_back({90, lines.back().t + 0.1, lines.back().T});
  fixture_.writeRun(fixture_.framesTrue(), lines, fixture_.calibrationEqualToTruth());
  expectInputError([&] { load(); }, fixture_.run() / "trajectory/uhi_lines.csv",
                   "line 92: scan line 90 is not in the survey (" +
                       (fixture_.survey() / "uhi/lines.csv").string() +
                       " holds lines 0 to 89)");
}

TEST_F(EvaluationInputsTest, ATruthOfAnotherSurveyIsRefused) {
  fixture_.writeRunEqualToTruth();
  // Frame 3's truth 10 us late: it no longer is the pose of frame 3.
  std::vector<TruthPose> frames = readTruthPoses(fixture_.truth() / "rgb_poses.csv");
  frames[3].t += 1e-5;
  writeTruthPoses(fixture_.truth() / "rgb_poses.csv", frames);
  expectInputError([&] { load(); }, fixture_.truth() / "rgb_poses.csv",
                   "line 5: t = " + formatDouble(frames[3].t) +
                       ", but frame 3 of the survey (t = " + t(3) + ") has no row before it: " +
                       framesRule());

  fixture_.writeTruth();
  std::vector<TruthLinePose> lines = readTruthLinePoses(fixture_.truth() / "uhi_poses.csv");
  lines.resize(80);
  writeTruthLinePoses(fixture_.truth() / "uhi_poses.csv", lines);
  expectInputError([&] { load(); }, fixture_.truth() / "uhi_poses.csv",
                   " holds scan lines 0 to 79, expected every scan line of " +
                       (fixture_.survey() / "uhi/lines.csv").string() +
                       ", 0 to 89: line 80 is missing");
}

TEST_F(EvaluationInputsTest, TruthLineTimesMustBeRecordedTimePlusTheTrueOffset) {
  fixture_.writeRunEqualToTruth();
  TruthCalibration calibration = fixture_.calibrationTrue();
  calibration.time_offset_s = 0.02;
  writeTruthCalibration(fixture_.truth() / "calibration.yaml", calibration);
  expectInputError([&] { load(); }, fixture_.truth() / "uhi_poses.csv",
                   "line 2: t = " + formatDouble(36000.0 + testing::kTrueTimeOffset) +
                       ", expected " + formatDouble(36000.0 + 0.02) +
                       " = scan line 0's recorded time 36000 (" +
                       (fixture_.survey() / "uhi/lines.csv").string() +
                       ") + time_offset_s 0.02 (" +
                       (fixture_.truth() / "calibration.yaml").string() + "), within 1e-06 s");
}

TEST_F(EvaluationInputsTest, FilesOfTwoRunsAreRefused) {
  RunCalibration calibration = fixture_.calibrationEqualToTruth();
  calibration.variant = "joint";
  fixture_.writeRun(fixture_.framesTrue(), fixture_.linesTrue(), calibration);
  expectInputError([&] { load(); }, fixture_.run() / "calibration.yaml",
                   "key variant: variant 'joint' differs from the variant 'sequential' of " +
                       (fixture_.run() / "run.yaml").string() +
                       "; expected the files of one run");
}

TEST_F(EvaluationInputsTest, MissingResultsFilesAndWrongTruthFolderAreNamed) {
  fixture_.writeRunEqualToTruth();
  std::filesystem::remove(fixture_.run() / "calibration.yaml");
  expectInputError([&] { load(); }, fixture_.run() / "calibration.yaml",
                   " missing: expected the estimated calibration calibration.yaml, written by "
                   "`hsmap run` (docs/EVALUATE.md)");
  expectInputError([&] { loadEvaluationInputs(fixture_.run(), fixture_.survey()); },
                   fixture_.survey(),
                   " expected the truth/ folder of a simulated survey (SURVEY/truth), got a "
                   "folder named 'survey'");
}

}  // namespace
}  // namespace hsmap
