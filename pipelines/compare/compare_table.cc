#include "pipelines/compare/compare_table.h"

#include "pipelines/run/stage_table.h"

#include <algorithm>
#include <cstdio>
#include <functional>

namespace hsmap {

namespace {

// Keys in first-seen order over every variant.
std::vector<std::string> unionOfKeys(const std::vector<std::vector<std::string>>& lists) {
  std::vector<std::string> keys;
  for (const auto& list : lists) {
    for (const std::string& key : list) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  return keys;
}

// A failed variant's figures (its time until it failed) are shown but never
// the best.
CompareRow makeRow(const std::string& key, const std::vector<VariantOutcome>& variants,
                   const std::function<std::optional<double>(std::size_t)>& value_of) {
  CompareRow row;
  row.key = key;
  row.better = metricDirection(key);
  std::vector<std::optional<double>> candidates;
  for (std::size_t c = 0; c < variants.size(); ++c) {
    row.values.push_back(value_of(c));
    candidates.push_back(variants[c].succeeded() ? row.values.back() : std::nullopt);
  }
  row.best = bestOf(row.better, candidates);
  return row;
}

}  // namespace

std::vector<bool> bestOf(Better better, const std::vector<std::optional<double>>& values) {
  std::vector<bool> best(values.size(), false);
  if (better == Better::none) return best;
  std::optional<double> target;
  for (const auto& value : values) {
    if (!value) continue;
    if (!target || (better == Better::lower ? *value < *target : *value > *target)) target = value;
  }
  for (std::size_t i = 0; i < values.size(); ++i) best[i] = target && values[i] && *values[i] == *target;
  return best;
}

std::string bestVariants(const CompareTable& table, const CompareRow& row) {
  std::string names;
  for (std::size_t i = 0; i < row.best.size() && i < table.variants.size(); ++i) {
    if (row.best[i]) names += (names.empty() ? "" : " ") + table.variants[i].variant;
  }
  return names;
}

CompareTable buildCompareTable(std::vector<VariantOutcome> variants) {
  CompareTable table;
  table.variants = std::move(variants);

  table.time_rows.push_back(makeRow("wall_time_s", table.variants, [&](std::size_t c) -> std::optional<double> {
    return table.variants[c].wall_time_s;
  }));
  std::vector<std::vector<std::string>> stage_names, metric_keys;
  for (const VariantOutcome& variant : table.variants) {
    stage_names.emplace_back();
    for (const StageTime& stage : variant.stages) stage_names.back().push_back(stage.stage);
    metric_keys.emplace_back();
    for (const auto& [key, value] : variant.metrics) metric_keys.back().push_back(key);
  }
  // Stages in run order (load first), whichever variant ran them.
  std::vector<std::string> stages = unionOfKeys(stage_names);
  std::vector<std::string> order = {"load"};
  for (StageId id : allStages()) order.push_back(stageDefinition(id).name);
  std::stable_sort(stages.begin(), stages.end(), [&](const std::string& a, const std::string& b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
  for (const std::string& stage : stages) {
    table.time_rows.push_back(makeRow("time_s." + stage, table.variants, [&](std::size_t c) -> std::optional<double> {
      for (const StageTime& time : table.variants[c].stages) {
        if (time.stage == stage) return time.time_s;
      }
      return std::nullopt;
    }));
  }
  for (const std::string& key : unionOfKeys(metric_keys)) {
    table.metric_rows.push_back(makeRow(key, table.variants, [&](std::size_t c) -> std::optional<double> {
      for (const auto& [name, value] : table.variants[c].metrics) {
        if (name == key) return value;
      }
      return std::nullopt;
    }));
  }
  return table;
}

}  // namespace hsmap

namespace hsmap {

std::string displayFigure(const std::optional<double>& value) {
  if (!value) return "—";
  char text[32];
  std::snprintf(text, sizeof(text), "%.4g", *value);
  return text;
}

}  // namespace hsmap
