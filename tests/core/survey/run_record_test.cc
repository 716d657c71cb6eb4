#include "core/survey/run_record.h"

#include <gtest/gtest.h>

#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

RunRecord exampleRecord() {
  RunRecord record;
  record.program_version = "0.1.0";
  record.variant = "sequential";
  record.survey = "/data/dives/rugged survey";
  record.started_utc = "2026-12-01T23:30:00Z";
  record.options = {{"until", "georef"}, {"surface", "dense"}, {"note", ""}};
  record.stages = {{"frontend", 12.5, 240.1}, {"georef", 3.2, 300.0}};
  record.total_time_s = 15.9;
  record.peak_rss_mb = 300.0;
  return record;
}

class RunRecordTest : public ::testing::Test {
 protected:
  TempFolder folder_{"run-record"};
  std::filesystem::path path_ = folder_ / "run.yaml";

  std::filesystem::path variant(const std::string& from, const std::string& to) {
    writeRunRecord(path_, exampleRecord());
    testing::replaceInFile(path_, from, to);
    return path_;
  }
};

TEST_F(RunRecordTest, RoundTripsExactly) {
  const RunRecord record = exampleRecord();
  writeRunRecord(path_, record);
  const RunRecord read = readRunRecord(path_);
  EXPECT_EQ(read.program_name, "hsmap");
  EXPECT_EQ(read.program_version, "0.1.0");
  EXPECT_EQ(read.variant, "sequential");
  EXPECT_EQ(read.survey, record.survey);
  EXPECT_EQ(read.started_utc, record.started_utc);
  EXPECT_EQ(read.options, record.options);
  ASSERT_EQ(read.stages.size(), 2u);
  EXPECT_EQ(read.stages[1].name, "georef");
  EXPECT_EQ(read.stages[1].time_s, 3.2);
  EXPECT_EQ(read.stages[1].peak_rss_mb, 300.0);
  EXPECT_EQ(read.total_time_s, 15.9);
  EXPECT_EQ(read.peak_rss_mb, 300.0);
  writeRunRecord(folder_ / "again.yaml", read);
  EXPECT_EQ(TempFolder::read(folder_ / "again.yaml"), TempFolder::read(path_));
}

TEST_F(RunRecordTest, TheWrittenFileLooksAsDocumented) {
  writeRunRecord(path_, exampleRecord());
  EXPECT_EQ(TempFolder::read(path_),
            "# hsmap run record (format: see docs/EVALUATE.md)\n"
            "format: hsmap-run/1\n"
            "program: {name: hsmap, version: \"0.1.0\"}\n"
            "variant: sequential\n"
            "survey: /data/dives/rugged survey\n"
            "started_utc: \"2026-12-01T23:30:00Z\"\n"
            "options: {note: \"\", surface: dense, until: georef}\n"
            "stages:\n"
            "  - {name: frontend, time_s: 12.5, peak_rss_mb: 240.1}\n"
            "  - {name: georef, time_s: 3.2, peak_rss_mb: 300}\n"
            "total_time_s: 15.9\n"
            "peak_rss_mb: 300\n");
}

TEST_F(RunRecordTest, ReadsBlockStyleAndEmptyCollections) {
  writeText(path_,
            "format: hsmap-run/1\n"
            "program:\n"
            "  name: hsmap\n"
            "  version: \"0.2.0\"\n"
            "variant: joint\n"
            "survey: /s\n"
            "started_utc: \"2026-01-31T00:00:59Z\"\n"
            "options:\n"
            "  until: products\n"
            "  null_text: \"null\"\n"
            "stages: []\n"
            "total_time_s: 0\n"
            "peak_rss_mb: 12\n");
  const RunRecord read = readRunRecord(path_);
  EXPECT_EQ(read.options.at("until"), "products");
  EXPECT_EQ(read.options.at("null_text"), "null");
  EXPECT_TRUE(read.stages.empty());
  // A text that YAML would read as null survives a round trip.
  writeRunRecord(folder_ / "again.yaml", read);
  EXPECT_EQ(readRunRecord(folder_ / "again.yaml").options, read.options);
}

TEST_F(RunRecordTest, BadInputsAreNamedByLineAndKey) {
  expectInputError([&] { readRunRecord(variant("variant: sequential", "variant: sequental")); },
                   path_,
                   "line 4, key variant: unknown variant 'sequental'; expected one of: stacked, "
                   "planar, sequential, joint");
  expectInputError(
      [&] { readRunRecord(variant("name: georef, time_s: 3.2", "name: frontend, time_s: 3.2")); },
      path_, "line 10, key stages[1].name: duplicated stage 'frontend' (first at line 9)");
  expectInputError(
      [&] { readRunRecord(variant("time_s: 3.2", "time_s: -3.2")); }, path_,
      "line 10, key stages[1].time_s: expected a number >= 0, got -3.2");
  expectInputError(
      [&] {
        readRunRecord(variant("survey: /data/dives/rugged survey", "survey: data/dives/rugged"));
      },
      path_,
      "line 5, key survey: expected the survey folder as an absolute path, got 'data/dives/rugged'");
  expectInputError(
      [&] { readRunRecord(variant("2026-12-01T23:30:00Z", "2026-12-01 23:30")); }, path_,
      "line 6, key started_utc: expected a UTC time \"YYYY-MM-DDTHH:MM:SSZ\", got "
      "'2026-12-01 23:30'");
  expectInputError([&] { readRunRecord(variant("surface: dense", "surface: [dense]")); }, path_,
                   "line 7, key options.surface: expected a text value (\"\" for an empty one), "
                   "got a list");
  expectInputError([&] { readRunRecord(variant("name: georef", "name: total")); }, path_,
                   "line 10, key stages[1].name: 'total' is reserved (metrics.json's timings_s "
                   "uses it for the whole run); expected another stage name");
  expectInputError([&] { readRunRecord(variant("total_time_s: 15.9\n", "")); }, path_,
                   "line 2, key total_time_s: missing required key");
}

TEST_F(RunRecordTest, WriterRefusesARelativeSurveyPath) {
  RunRecord record = exampleRecord();
  record.survey = "relative/survey";
  EXPECT_THROW(writeRunRecord(path_, record), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path_));
}

TEST(UtcTimestamp, FormatsWholeSecondsInUtc) {
  // 2026-12-01T23:30:00Z is 1796167800 s after the Unix epoch.
  const auto time = std::chrono::system_clock::time_point(std::chrono::seconds(1796167800));
  EXPECT_EQ(formatUtcTimestamp(time + std::chrono::milliseconds(900)), "2026-12-01T23:30:00Z");
}

}  // namespace
}  // namespace hsmap
