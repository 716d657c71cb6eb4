#pragma once
// `hsmap report RUN`: writes RUN/report/index.html, the run's report
// (docs/REPORT.md), from the run folder as it is: what `hsmap run` writes at
// its end, written again (e.g. after moving the run, or with an hsmap whose
// report shows more). A malformed file of the run folder is an InputError
// (exit status 2, one line naming the file and the line or key).

#include <filesystem>
#include <iosfwd>

namespace CLI {
class App;
}

namespace hsmap {

struct ReportOptions {
  std::filesystem::path run;  // the results folder of `hsmap run ... --out RUN`
};

CLI::App* addReportCommand(CLI::App& app, ReportOptions& options);

// Returns the exit status: 0 when written; 1 when RUN is not a run folder
// (message on `err`). Throws InputError for a malformed file in it.
int runReportCommand(const ReportOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
