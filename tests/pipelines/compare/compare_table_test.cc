// The compare table's rows (pipelines/compare/compare_table.h): the best of
// each row by its direction, ties, missing figures, failed variants, and the
// stage times in run order.

#include "pipelines/compare/compare_table.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

VariantOutcome outcome(const std::string& variant, MetricFigures metrics, std::vector<StageTime> stages = {}) {
  VariantOutcome result;
  result.variant = variant;
  result.metrics = std::move(metrics);
  result.stages = std::move(stages);
  result.wall_time_s = 1.0;
  return result;
}

const CompareRow& row(const CompareTable& table, const std::string& key) {
  for (const auto* rows : {&table.metric_rows, &table.time_rows}) {
    for (const CompareRow& candidate : *rows) {
      if (candidate.key == key) return candidate;
    }
  }
  throw std::runtime_error("no row " + key);
}

TEST(CompareTable, TheBestIsTheLowestErrorAndTheHighestCoverage) {
  const CompareTable table = buildCompareTable(
      {outcome("planar", {{"rgb_ate_m", 0.07}, {"mesh_completeness", 0.0}, {"ortho_coverage", 0.88}}),
       outcome("sequential", {{"rgb_ate_m", 0.06}, {"mesh_completeness", 0.99}, {"ortho_coverage", 0.94}})});
  EXPECT_EQ(row(table, "rgb_ate_m").better, Better::lower);
  EXPECT_EQ(row(table, "rgb_ate_m").best, (std::vector<bool>{false, true}));
  EXPECT_EQ(row(table, "mesh_completeness").better, Better::higher);
  EXPECT_EQ(row(table, "mesh_completeness").best, (std::vector<bool>{false, true}));
  EXPECT_EQ(row(table, "ortho_coverage").best, (std::vector<bool>{false, true}));
  EXPECT_EQ(bestVariants(table, row(table, "rgb_ate_m")), "sequential");
}

TEST(CompareTable, EveryVariantThatTiesIsBest) {
  const CompareTable table = buildCompareTable({outcome("planar", {{"extrinsic_rotation_error_deg", 2.0}}),
                                                outcome("sequential", {{"extrinsic_rotation_error_deg", 2.0}}),
                                                outcome("joint", {{"extrinsic_rotation_error_deg", 2.5}})});
  EXPECT_EQ(row(table, "extrinsic_rotation_error_deg").best, (std::vector<bool>{true, true, false}));
  EXPECT_EQ(bestVariants(table, row(table, "extrinsic_rotation_error_deg")), "planar sequential");
}

TEST(CompareTable, MissingFiguresAreNeverBestAndARowWithoutValuesHasNone) {
  const CompareTable table =
      buildCompareTable({outcome("stacked", {{"rgb_ate_m", std::nullopt}, {"ortho_mean_shift_m", std::nullopt}}),
                         outcome("planar", {{"rgb_ate_m", 0.07}, {"ortho_mean_shift_m", std::nullopt}}),
                         outcome("sequential", {{"ortho_mean_shift_m", std::nullopt}})});  // no rgb_ate_m key
  const CompareRow& ate = row(table, "rgb_ate_m");
  EXPECT_FALSE(ate.values[0]);
  EXPECT_EQ(ate.values[1], 0.07);
  EXPECT_FALSE(ate.values[2]);
  EXPECT_EQ(ate.best, (std::vector<bool>{false, true, false}));
  EXPECT_EQ(row(table, "ortho_mean_shift_m").best, (std::vector<bool>{false, false, false}));
}

TEST(CompareTable, FiguresOfTheSurveyHaveNoBest) {
  const CompareTable table = buildCompareTable(
      {outcome("planar", {{"ins_floor_rgb_ate_m", 0.06}, {"alignment_view_distance_m", 1.2}}),
       outcome("joint", {{"ins_floor_rgb_ate_m", 0.05}, {"alignment_view_distance_m", 1.1}})});
  for (const char* key : {"ins_floor_rgb_ate_m", "alignment_view_distance_m"}) {
    EXPECT_EQ(row(table, key).better, Better::none) << key;
    EXPECT_EQ(row(table, key).best, (std::vector<bool>{false, false})) << key;
  }
  EXPECT_EQ(metricDirection("a_metric_of_a_later_hsmap"), Better::none);
}

TEST(CompareTable, AFailedVariantShowsItsTimeButIsNeverBest) {
  VariantOutcome failed = outcome("joint", {}, {{"load", 0.1}, {"frontend", 2.0}});
  failed.status = "failed: stage joint failed: too few tie points";
  failed.wall_time_s = 0.5;
  const CompareTable table =
      buildCompareTable({outcome("sequential", {{"rgb_ate_m", 0.06}}, {{"load", 0.2}, {"frontend", 3.0}}), failed});
  EXPECT_FALSE(table.variants[1].succeeded());
  EXPECT_EQ(row(table, "wall_time_s").values[1], 0.5);
  EXPECT_EQ(row(table, "wall_time_s").best, (std::vector<bool>{true, false}));
  EXPECT_EQ(row(table, "time_s.frontend").best, (std::vector<bool>{true, false}));
  EXPECT_EQ(row(table, "rgb_ate_m").values[1], std::nullopt);
}

TEST(CompareTable, StageTimesFollowTheRunOrderWhicheverVariantComesFirst) {
  const CompareTable table =
      buildCompareTable({outcome("stacked", {}, {{"load", 0.1}, {"products", 1.0}}),
                         outcome("sequential", {}, {{"load", 0.1}, {"frontend", 3.0}, {"georef", 0.4},
                                                    {"surface", 2.0}, {"refine", 0.2}, {"products", 0.7}})});
  std::vector<std::string> keys;
  for (const CompareRow& time : table.time_rows) keys.push_back(time.key);
  EXPECT_EQ(keys, (std::vector<std::string>{"wall_time_s", "time_s.load", "time_s.frontend", "time_s.georef",
                                            "time_s.surface", "time_s.refine", "time_s.products"}));
}

TEST(CompareTable, FiguresForPeopleKeepFourDigits) {
  EXPECT_EQ(displayFigure(0.0123456), "0.01235");
  EXPECT_EQ(displayFigure(263.64), "263.6");
  EXPECT_EQ(displayFigure(std::nullopt), "—");
}

}  // namespace
}  // namespace hsmap
