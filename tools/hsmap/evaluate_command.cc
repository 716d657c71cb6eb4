#include "tools/hsmap/evaluate_command.h"

#include <CLI/CLI.hpp>
#include <ostream>

#include "pipelines/evaluate/evaluate_run.h"
#include "pipelines/report/run_report.h"

namespace hsmap {

CLI::App* addEvaluateCommand(CLI::App& app, EvaluateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "evaluate", "Score a run's results against a simulated survey's ground truth");
  command->footer(
      "Reads RUN/run.yaml, RUN/trajectory/frames.csv, RUN/trajectory/uhi_lines.csv and "
      "RUN/calibration.yaml, the survey (the parent of --truth) and its truth/, checks that "
      "their rows correspond (frames by time within 1 us, scan lines by index), writes "
      "RUN/metrics.json and prints the figures: trajectory errors before and after a similarity "
      "alignment, scan-line pose errors, extrinsic and time-offset errors, the mesh metrics when "
      "the run has RUN/map/mesh.ply (under the frames' alignment and, as hsmap's extension, under "
      "an alignment whose rotation comes from the frames' orientations, with the track's "
      "cross-track spread that tells when positions alone align poorly), the ortho-image metrics "
      "when it has RUN/hyperspectral/ortho.hdr (against SURVEY/truth/reflectance.hdr), timings, "
      "peak memory, and the INS floor (what the INS alone allows for geo-referencing). Every "
      "metric is defined in docs/EVALUATE.md. When the run has a report (RUN/report/index.html), it is "
      "written again with the metrics and the ortho displacement field.\n"
      "Exit status: 0 on success; 2 when an input is missing, malformed or does not match the "
      "others, with one line naming the file, the line or key, and what was expected; 1 on "
      "other failures.");
  command->add_option("RUN", options.run, "Results folder written by `hsmap run ... --out RUN`")
      ->required();
  command->add_option("--truth", options.truth, "The survey's ground truth folder, SURVEY/truth")
      ->required();
  return command;
}

int runEvaluateCommand(const EvaluateOptions& options, std::ostream& out) {
  const EvaluationReport report = evaluateRunFolder(options.run, options.truth);
  for (const std::string& warning : report.warnings) out << "warning: " << warning << "\n";
  printMetricsTable(out, report.metrics);
  out << "wrote " << report.metrics_path.string();
  if (!report.ortho_patches_path.empty()) out << " and " << report.ortho_patches_path.string();
  out << "\n";
  // A run's report shows the metrics once they exist: the one `hsmap run`
  // wrote is written again with them (a run without a report gets none).
  std::error_code error;
  if (std::filesystem::is_regular_file(runReportPath(options.run), error)) {
    const RunReport page = writeRunReport(options.run);
    out << "report: " << page.path.string() << " (with the metrics)\n";
  }
  return 0;
}

}  // namespace hsmap
