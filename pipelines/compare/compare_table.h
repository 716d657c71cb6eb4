#pragma once
// The table of `hsmap compare` (docs/COMPARE.md): one column per variant, in
// the order asked for; rows of figures with the best of each row marked.
//
//   status          "ok", or "failed: <why>" (a variant that failed is a
//                   column of its own; its figures are missing)
//   wall_time_s     the variant's run and evaluation in this compare
//   time_s.<stage>  each stage's time from the variant's run.yaml (a stage
//                   shared with another variant: the time it took there,
//                   named in shared_stages / shared_from)
//   <metric>        every scalar of the variants' metrics.json, in the
//                   file's order (EVALUATE.md), null or absent = missing
//
// Best per row: the smallest value where lower is better, the largest where
// higher is (metric_direction.h); every variant that ties is marked; a row
// with no direction, or no value, has no best.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pipelines/compare/metric_direction.h"
#include "pipelines/compare/metrics_file.h"

namespace hsmap {

struct StageTime {
  std::string stage;
  double time_s = 0.0;
};

// What one variant of the compare gave.
struct VariantOutcome {
  std::string variant;
  std::string status = "ok";  // "ok" or "failed: <why>"
  double wall_time_s = 0.0;
  std::vector<StageTime> stages;  // run.yaml's, in the order they ran (load first)
  // The stages taken from another variant's run (up to date there, linked in).
  std::vector<std::string> shared_stages;
  std::string shared_from;
  MetricFigures metrics;  // metrics.json's; empty when not evaluated
  std::filesystem::path quicklook;  // the ortho-image's quick-look, when the run has one (not in the CSV)

  bool succeeded() const { return !status.starts_with("failed"); }
};

struct CompareRow {
  std::string key;
  Better better = Better::none;
  std::vector<std::optional<double>> values;  // one per variant
  std::vector<bool> best;                     // one per variant
};

struct CompareTable {
  std::vector<VariantOutcome> variants;
  std::vector<CompareRow> time_rows;    // wall_time_s, then time_s.<stage> in run order
  std::vector<CompareRow> metric_rows;  // the metrics' keys, in metrics.json's order
};

// The rows from the variants' figures, best marked.
CompareTable buildCompareTable(std::vector<VariantOutcome> variants);

// Which values are the best of a row (all false for Better::none or when
// every value is missing).
std::vector<bool> bestOf(Better better, const std::vector<std::optional<double>>& values);

// The names of the variants marked best in `row`, separated by spaces.
std::string bestVariants(const CompareTable& table, const CompareRow& row);

}  // namespace hsmap

namespace hsmap {

// A figure for people: four significant digits ("0.01234", "263.6"), "—"
// when missing.
std::string displayFigure(const std::optional<double>& value);

}  // namespace hsmap
