// compare.csv (pipelines/compare/compare_csv.h): what is written reads back
// the same, quoting included, and a damaged file is an error naming its line.

#include "pipelines/compare/compare_csv.h"

#include <gtest/gtest.h>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

CompareTable sampleTable() {
  VariantOutcome planar;
  planar.variant = "planar";
  planar.wall_time_s = 263.640000001;
  planar.stages = {{"load", 0.0123}, {"georef", 0.04}, {"surface", 7.0}, {"products", 256.6}};
  planar.metrics = {{"rgb_ate_m", 0.07481234567890123}, {"ortho_mean_shift_m", std::nullopt},
                    {"mesh_completeness", 0.0}};
  VariantOutcome joint;
  joint.variant = "joint";
  joint.status = "failed: stage joint failed: \"T_C_U\" undetermined, 3 tie points\nsee the log";
  joint.wall_time_s = 61.5;
  joint.stages = {{"load", 0.02}, {"frontend", 71.5}};
  joint.shared_stages = {"frontend", "georef", "surface"};
  joint.shared_from = "sequential";
  return buildCompareTable({planar, joint});
}

TEST(CompareCsv, WhatIsWrittenReadsBackTheSame) {
  const testing::TempFolder temp;
  const CompareTable table = sampleTable();
  writeCompareCsv(temp / "compare.csv", table);
  const CompareTable read = readCompareCsv(temp / "compare.csv");

  ASSERT_EQ(read.variants.size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(read.variants[c].variant, table.variants[c].variant);
    EXPECT_EQ(read.variants[c].status, table.variants[c].status);
    EXPECT_EQ(read.variants[c].shared_stages, table.variants[c].shared_stages);
    EXPECT_EQ(read.variants[c].shared_from, table.variants[c].shared_from);
    EXPECT_EQ(read.variants[c].wall_time_s, table.variants[c].wall_time_s);  // to the last bit
  }
  EXPECT_EQ(read.variants[0].stages.size(), 4u);
  EXPECT_EQ(read.variants[1].stages[1].stage, "frontend");
  EXPECT_EQ(read.variants[1].stages[1].time_s, 71.5);
  for (const auto& [rows, read_rows] :
       {std::pair{&table.time_rows, &read.time_rows}, std::pair{&table.metric_rows, &read.metric_rows}}) {
    ASSERT_EQ(read_rows->size(), rows->size());
    for (std::size_t r = 0; r < rows->size(); ++r) {
      EXPECT_EQ((*read_rows)[r].key, (*rows)[r].key);
      EXPECT_EQ((*read_rows)[r].better, (*rows)[r].better) << (*rows)[r].key;
      EXPECT_EQ((*read_rows)[r].values, (*rows)[r].values) << (*rows)[r].key;
      EXPECT_EQ((*read_rows)[r].best, (*rows)[r].best) << (*rows)[r].key;
    }
  }
  // Written again, the same bytes.
  EXPECT_EQ(compareCsv(read), compareCsv(table));
}

TEST(CompareCsv, TheFileStartsWithItsHeaderAndTheVariantsStatus) {
  const std::string text = compareCsv(sampleTable());
  EXPECT_EQ(text.substr(0, text.find('\n')), "key,better,best,planar,joint");
  EXPECT_NE(text.find("\nrgb_ate_m,lower,planar,0.07481234567890123,\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nmesh_completeness,higher,planar,0,\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nshared_stages,,,,frontend georef surface\n"), std::string::npos) << text;
}

void expectError(const std::string& text, const std::string& message) {
  try {
    parseCompareCsv(text, "DIR/compare.csv");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), message);
  }
}

TEST(CompareCsv, ADamagedFileIsAnErrorNamingItsLine) {
  expectError("metric,stacked\n",
              "DIR/compare.csv:line 1: expected the header key,better,best and one column per variant");
  expectError("key,better,best,planar\nstatus,,,ok\nrgb_ate_m,lower,,abc\n",
              "DIR/compare.csv:line 3: column 'planar': expected a number or nothing, got 'abc'");
  expectError("key,better,best,planar\nrgb_ate_m,lower,\n",
              "DIR/compare.csv:line 2: expected 4 fields, got 3");
  expectError("key,better,best,planar\nrgb_ate_m,smaller,,1\n",
              "DIR/compare.csv:line 2: column 'better': expected lower, higher or nothing, got 'smaller'");
  expectError("key,better,best,planar\nstatus,,,\"failed\n",
              "DIR/compare.csv:line 2: a quoted field that does not end");
}

}  // namespace
}  // namespace hsmap
