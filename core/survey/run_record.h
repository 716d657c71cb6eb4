#pragma once
// RUN/run.yaml: what ran to produce a results folder (docs/EVALUATE.md):
//
//   format: hsmap-run/1
//   program: {name: hsmap, version: "0.1.0"}
//   variant: sequential                  stacked | planar | sequential | joint
//   survey: /absolute/path/to/survey
//   started_utc: "2026-12-01T23:30:00Z"
//   options: {until: georef, ...}        text -> text, flow or block style, may be {}
//   stages:                              in the order they ran, may be []
//     - {name: frontend, time_s: 12.5, peak_rss_mb: 240.1}
//     - {name: georef, time_s: 3.2, peak_rss_mb: 300.0}
//   total_time_s: 15.9
//   peak_rss_mb: 300.0
//
// Rules (strict_yaml_map.h: unknown, duplicated or missing keys are errors):
//   - survey is an absolute path: the record must still name the survey when
//     read from another working directory;
//   - started_utc is ISO 8601 UTC to the second, "YYYY-MM-DDTHH:MM:SSZ";
//   - option names are non-empty texts, each at most once; values are texts
//     (possibly empty, written "");
//   - stage names are non-empty, unique and not "total": metrics.json's
//     timings_s uses them as keys beside "total";
//   - times and memory are finite numbers >= 0 (seconds, MiB).
// Errors are InputError naming the file, line and key, e.g.
//   "RUN/run.yaml:line 9, key stages[1].name: duplicated stage 'georef' (first at line 8)".
// Writing is atomic, numbers in shortest round-trip form, and runs the
// reader's checks first (std::invalid_argument for a record it would refuse).

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hsmap {

struct StageRecord {
  std::string name;
  double time_s = 0.0;       // wall time
  double peak_rss_mb = 0.0;  // peak resident memory of the process when the stage ended
};

struct RunRecord {
  static constexpr const char* kFormat = "hsmap-run/1";
  std::string program_name = "hsmap";
  std::string program_version;
  std::string variant;            // one of runVariants() (run_variants.h)
  std::filesystem::path survey;   // absolute
  std::string started_utc;        // "YYYY-MM-DDTHH:MM:SSZ"
  std::map<std::string, std::string> options;
  std::vector<StageRecord> stages;
  double total_time_s = 0.0;
  double peak_rss_mb = 0.0;
};

RunRecord readRunRecord(const std::filesystem::path& file);
// The same on the file's content `text`; `file` names it in errors.
RunRecord parseRunRecord(std::string_view text, const std::filesystem::path& file);
void writeRunRecord(const std::filesystem::path& file, const RunRecord& record);

// `time` as run.yaml's started_utc: "2026-12-01T23:30:00Z" (UTC, whole seconds).
std::string formatUtcTimestamp(std::chrono::system_clock::time_point time);

}  // namespace hsmap
