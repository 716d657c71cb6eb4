#include "core/survey/survey_summary.h"

#include <gtest/gtest.h>

#include <sstream>

#include "pipelines/sample_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

TEST(AnalyzeTimeStamps, RegularStreamHasItsRateAndNoGaps) {
  std::vector<double> times;
  for (int i = 0; i < 50; ++i) times.push_back(100.0 + 0.04 * i);
  const StreamTiming timing = analyzeTimeStamps(times);
  EXPECT_EQ(timing.count, 50u);
  EXPECT_EQ(timing.first_t, 100.0);
  EXPECT_EQ(timing.last_t, 100.0 + 0.04 * 49);
  EXPECT_NEAR(timing.median_step_s, 0.04, 1e-12);
  EXPECT_NEAR(timing.rate_hz, 25.0, 1e-9);
  EXPECT_EQ(timing.gap_count, 0u);
  EXPECT_TRUE(timing.first_gaps.empty());
}

TEST(AnalyzeTimeStamps, StepsLongerThanOneAndAHalfMediansAreGaps) {
  // 0.1 s steps; a dropped sample (0.2 s) after index 4, a 1.4x step (not a
  // gap) after index 9 and a long outage after index 14.
  std::vector<double> times;
  double t = 0.0;
  for (int i = 0; i < 30; ++i) {
    times.push_back(t);
    t += (i == 4) ? 0.2 : (i == 9) ? 0.14 : (i == 14) ? 3.0 : 0.1;
  }
  const StreamTiming timing = analyzeTimeStamps(times, 1);
  EXPECT_NEAR(timing.median_step_s, 0.1, 1e-12);
  EXPECT_EQ(timing.gap_count, 2u);
  ASSERT_EQ(timing.first_gaps.size(), 1u);  // listing capped at 1
  EXPECT_EQ(timing.first_gaps[0].index, 5u);
  EXPECT_EQ(timing.first_gaps[0].t_before, times[4]);
  EXPECT_EQ(timing.first_gaps[0].t_after, times[5]);
  const StreamTiming all = analyzeTimeStamps(times);
  ASSERT_EQ(all.first_gaps.size(), 2u);
  EXPECT_EQ(all.first_gaps[1].index, 15u);
}

TEST(AnalyzeTimeStamps, EvenNumberOfStepsUsesTheMeanOfTheMiddleTwo) {
  const StreamTiming timing = analyzeTimeStamps({0.0, 1.0, 3.0});  // steps 1 and 2
  EXPECT_DOUBLE_EQ(timing.median_step_s, 1.5);
  EXPECT_EQ(timing.gap_count, 0u);  // 2 < 1.5 * 1.5
}

TEST(AnalyzeTimeStamps, SingleAndNoTimeStamps) {
  const StreamTiming one = analyzeTimeStamps({5.0});
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.first_t, 5.0);
  EXPECT_EQ(one.rate_hz, 0.0);
  EXPECT_EQ(analyzeTimeStamps({}).count, 0u);
}

TEST(SummarizeSurvey, SampleSurvey) {
  testing::TempFolder temp("summary");
  writeSampleSurvey(temp / "sample");
  const SurveySummary summary = summarizeSurvey(loadSurvey(temp / "sample"));
  EXPECT_EQ(summary.name, "hsmap-sample");
  EXPECT_EQ(summary.rgb.count, 75u);
  EXPECT_NEAR(summary.rgb.rate_hz, 25.0, 1e-6);
  EXPECT_EQ(summary.uhi.count, 90u);
  EXPECT_NEAR(summary.uhi.rate_hz, 30.0, 1e-6);
  EXPECT_EQ(summary.ins.count, 6u);
  EXPECT_NEAR(summary.ins.rate_hz, 1.0, 1e-9);
  EXPECT_EQ(summary.rgb.gap_count + summary.uhi.gap_count + summary.ins.gap_count, 0u);
  EXPECT_EQ(summary.uhi_samples, 64);
  EXPECT_EQ(summary.uhi_bands, 16);
  EXPECT_EQ(summary.uhi_lines, 90);
  EXPECT_EQ(summary.uhi_data_type, "uint16");
  EXPECT_EQ(summary.uhi_interleave, "bil");
  EXPECT_DOUBLE_EQ(summary.wavelength_min_nm, 400.0);
  EXPECT_DOUBLE_EQ(summary.wavelength_max_nm, 800.0);
  EXPECT_TRUE(summary.ins_has_attitude);
  EXPECT_TRUE(summary.origin_from_config);

  std::ostringstream text;
  printSurveySummary(text, summary);
  const std::string printed = text.str();
  for (const char* expected :
       {"survey 'hsmap-sample'", "RGB: pinhole-radtan 160x120",
        "UHI: pushbroom, 64 samples x 16 bands, 90 lines, uint16, bil",
        "wavelengths 400.0 - 800.0 nm", "INS: position and attitude",
        "RGB frames: 75 frames, t = [36000.000000, 36002.960000] s (2.960 s), 25.000 Hz",
        "UHI lines: 90 lines",
        "INS fixes: 6 fixes, t = [35999.000000, 36004.000000] s (5.000 s), 1.000 Hz",
        "origin: lat 43.00000000, lon 5.00000000, depth 0.000 m (given in survey.yaml)",
        "truth: none", "warnings: none"}) {
    EXPECT_NE(printed.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                         << printed;
  }
}

// inspect reads every frame whole: a truncated frame and a first frame with
// a changed byte are each named in a warning, with their frames.csv line;
// the survey still loads (the run bridges them as lost frames).
TEST(SummarizeSurvey, DamagedFramesAreNamedInTheWarnings) {
  testing::TempFolder temp("summary-damaged");
  writeSampleSurvey(temp / "sample");
  const Survey whole = loadSurvey(temp / "sample");
  ASSERT_TRUE(summarizeSurvey(whole).warnings.empty());
  const auto first = whole.rgb.framePath(0), tenth = whole.rgb.framePath(10);
  std::string bytes = testing::readText(tenth);
  const std::size_t cut = bytes.size() / 2;
  testing::writeText(tenth, bytes.substr(0, cut));
  bytes = testing::readText(first);
  bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 0x40);
  testing::writeText(first, bytes);

  const SurveySummary summary = summarizeSurvey(loadSurvey(temp / "sample"));
  ASSERT_EQ(summary.warnings.size(), 2u);
  EXPECT_EQ(summary.warnings[0].rfind("RGB frame 0 (" + first.string() + ", frames.csv line 2) is damaged: damaged: ", 0),
            0u) << summary.warnings[0];
  EXPECT_NE(summary.warnings[0].find("fails its CRC; the front-end will count it as a lost frame and bridge it"),
            std::string::npos) << summary.warnings[0];
  EXPECT_EQ(summary.warnings[1].rfind("RGB frame 10 (" + tenth.string() + ", frames.csv line 12) is damaged: truncated: "
                                      "the file ends at byte " + std::to_string(cut),
                                      0),
            0u) << summary.warnings[1];
}

TEST(PrintSurveySummary, ListsGapsTruthAndWarnings) {
  SurveySummary summary;
  summary.name = "gappy";
  summary.rgb = analyzeTimeStamps({0.0, 0.1, 0.2, 0.6, 0.7});
  summary.truth.present = true;
  summary.truth.found_files = {"scene.ply"};
  summary.truth.missing_files = {"uhi_poses.csv"};
  summary.warnings = {"something odd"};
  std::ostringstream text;
  printSurveySummary(text, summary);
  const std::string printed = text.str();
  EXPECT_NE(printed.find("gaps: 1 step(s) longer than 1.5x the median 0.100000 s:\n"
                         "      0.200000 -> 0.600000 s (step 0.400000 s, before entry 3)"),
            std::string::npos)
      << printed;
  EXPECT_NE(printed.find("truth: present (1 of 2 expected files; missing: uhi_poses.csv)"),
            std::string::npos)
      << printed;
  EXPECT_NE(printed.find("warnings:\n  - something odd\n"), std::string::npos) << printed;
}

}  // namespace
}  // namespace hsmap
