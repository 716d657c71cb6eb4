#pragma once
// RUN/report/index.html: the run's report (docs/REPORT.md), one
// self-contained page that opens offline in any browser. Written at the end
// of every `hsmap run`, by `hsmap report RUN`, and again by `hsmap evaluate`
// when a report exists (so that the metrics appear in it).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace hsmap {

struct RunReport {
  std::filesystem::path path;  // RUN/report/index.html
  std::uintmax_t bytes = 0;
  std::vector<std::string> notes;  // what the page does not show, and why
};

// RUN/report/index.html relative path, and the report of `run`'s path.
inline constexpr const char* kRunReportPath = "report/index.html";
std::filesystem::path runReportPath(const std::filesystem::path& run);

// Collects the run folder's data, assembles the page and writes it under a
// temporary name, renamed when complete (an older report stays whole until
// then). InputError for a malformed file of the run folder (naming the file
// and the line or key); std::runtime_error when `run` is not a run folder or
// the page cannot be written.
RunReport writeRunReport(const std::filesystem::path& run);

}  // namespace hsmap
