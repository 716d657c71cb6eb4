#include "pipelines/report/collect_run_summary.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "core/survey/run_record.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/text_file.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

// The stages that may have run, in the order a run runs them (docs/RUN.md).
constexpr const char* kStageNames[] = {"frontend", "georef", "surface", "refine", "joint", "products"};

// "warning: ..." lines (at any indentation) of a stage's summary.txt.
void collectSummaryWarnings(const fs::path& run, const std::string& stage, std::vector<std::string>& warnings) {
  const fs::path summary = run / stage / "summary.txt";
  std::error_code error;
  if (!fs::is_regular_file(summary, error)) return;
  const std::string text = readTextFile(summary, kMaxYamlBytes);
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos) continue;
    line.remove_prefix(first);
    constexpr std::string_view kPrefix = "warning: ";
    if (line.starts_with(kPrefix)) warnings.push_back(stage + ": " + std::string(line.substr(kPrefix.size())));
  }
}

// A stage record's scalar `key` (the records are the runner's own format,
// read here only for a run that has no run.yaml yet).
std::string recordValue(const YAML::Node& record, const char* key) {
  const YAML::Node value = record[key];
  return value && value.IsScalar() ? value.Scalar() : std::string();
}

double recordNumber(const YAML::Node& record, const char* key) {
  std::string message;
  return parseFiniteDouble(recordValue(record, key), &message).value_or(NAN);
}

}  // namespace

void collectRunSummary(const fs::path& run, ReportData& data) {
  std::error_code error;
  const fs::path run_yaml = run / results_paths::run_yaml;
  if (fs::is_regular_file(run_yaml, error)) {
    const RunRecord record = readRunRecord(run_yaml);
    data.run_complete = true;
    data.survey_folder = record.survey.string();
    data.variant = record.variant;
    data.program_version = record.program_version;
    data.started_utc = record.started_utc;
    for (const auto& [name, value] : record.options) data.options.emplace_back(name, value);
    for (const StageRecord& stage : record.stages) data.stages.push_back({stage.name, stage.time_s, stage.peak_rss_mb});
    data.total_time_s = record.total_time_s;
    data.peak_rss_mb = record.peak_rss_mb;
  } else {
    // A run stopped by a failing stage: what finished is in the stage records.
    data.notes.push_back(run_yaml.string() +
                         " is missing: the run did not finish (a stage failed or it was interrupted); stage times "
                         "come from the records of the stages that did");
    for (const char* name : kStageNames) {
      const fs::path file = run / "stages" / (std::string(name) + ".yaml");
      if (!fs::is_regular_file(file, error)) continue;
      const YAML::Node record = loadYamlFile(file);
      ReportStage stage{name, recordNumber(record, "time_s"), recordNumber(record, "peak_rss_mb")};
      data.stages.push_back(stage);
      if (data.survey_folder.empty()) data.survey_folder = recordValue(record, "survey");
      if (data.variant.empty()) data.variant = recordValue(record, "variant");
    }
  }

  const fs::path calibration = run / results_paths::calibration_yaml;
  if (fs::is_regular_file(calibration, error)) {
    data.calibration = readRunCalibration(calibration);
    data.calibration_source = calibration.string();
    for (const std::string& warning : data.calibration->warnings) {
      data.warnings.push_back("calibration.yaml: " + warning);
    }
  } else {
    data.notes.push_back("no calibration: " + calibration.string() + " is missing (the run stopped before a stage that writes it)");
  }
  std::vector<std::string> stage_warnings;
  for (const char* name : kStageNames) collectSummaryWarnings(run, name, stage_warnings);
  // The calibration repeats some of the stages' warnings word for word.
  for (const std::string& warning : stage_warnings) {
    const std::string text = warning.substr(warning.find(": ") + 2);
    const bool repeated = std::any_of(data.warnings.begin(), data.warnings.end(), [&](const std::string& known) {
      return known.ends_with(text);
    });
    if (!repeated) data.warnings.push_back(warning);
  }
}

}  // namespace hsmap
