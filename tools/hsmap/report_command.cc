#include "tools/hsmap/report_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <ostream>

#include "core/util/input_error.h"
#include "pipelines/report/run_report.h"

namespace hsmap {

CLI::App* addReportCommand(CLI::App& app, ReportOptions& options) {
  CLI::App* command = app.add_subcommand("report", "Write a run's report, RUN/report/index.html");
  command->footer(
      "Reads the run folder (run.yaml or the stage records, calibration.yaml, trajectory/, the stages' "
      "maps and summaries, the ortho-images, map/mesh.ply, metrics.json and report/ortho_patches.csv when "
      "`hsmap evaluate` wrote them) and the survey that run.yaml names, and writes one self-contained page "
      "that opens offline in any browser: the run's stages, times, memory and warnings, the trajectory with "
      "the INS fixes, the residual histograms, the calibration with its 1-sigma, the ortho-images side by "
      "side with spectra at chosen points, the mesh seen from above and, when scored, the metrics. "
      "`hsmap run` writes it at its end and `hsmap evaluate` refreshes it; this command writes it again. "
      "Every section is described in docs/REPORT.md.\n"
      "Exit status: 0 when written; 2 when a file of the run folder is malformed (one line naming the file, "
      "the line or key, and what was expected); 1 when RUN is not a run folder or on other failures.");
  command->add_option("RUN", options.run, "Results folder written by `hsmap run ... --out RUN`")->required();
  return command;
}

int runReportCommand(const ReportOptions& options, std::ostream& out, std::ostream& err) {
  try {
    const RunReport report = writeRunReport(options.run);
    for (const std::string& note : report.notes) out << "not shown: " << note << "\n";
    char size[32];
    std::snprintf(size, sizeof(size), "%.1f MB", double(report.bytes) / 1e6);
    out << "report: " << report.path.string() << " (" << size << ")\n";
    return 0;
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& failure) {
    err << "error: " << failure.what() << "\n";
    return 1;
  }
}

}  // namespace hsmap
