#include "tools/hsmap/compare_command.h"

#include <CLI/CLI.hpp>
#include <ostream>
#include <stdexcept>

#include "pipelines/compare/variant_list.h"
#include "tools/hsmap/child_process.h"

namespace hsmap {

CLI::App* addCompareCommand(CLI::App& app, CompareCommandLine& line) {
  CompareOptions& options = line.options;
  CLI::App* command = app.add_subcommand(
      "compare", "Run several variants on a survey, sharing their common stages, and tabulate them side by side");
  command->footer(
      "Runs each variant into DIR/VARIANT with `hsmap run` (its log in DIR/VARIANT.log), --jobs at a time, the "
      "stages two variants have in common once: joint takes frontend, georef and surface from sequential's "
      "run folder as soon as they are done. "
      "Evaluates each run when the survey has truth/ (`hsmap evaluate`), then writes DIR/compare.csv, "
      "DIR/compare.md and DIR/compare.html (a self-contained page): every metric x variant with the best of "
      "each row marked, the ortho-images' quick-looks side by side, the stage times per variant and the "
      "compare's wall time. A variant that fails is a column saying why; the others still run. On an "
      "existing DIR every run resumes. See docs/COMPARE.md.\n"
      "Exit status: 0 when every variant ran (and was evaluated); 1 for a usage error or when a variant "
      "failed; 2 when the survey is invalid.");
  command->add_option("SURVEY", options.survey, "Survey folder (the folder holding survey.yaml)")->required();
  command->add_option("--out", options.out, "Folder for the runs and the tables (created if absent)")->required();
  command->add_option("--variants", line.variants,
                      "Variants to run, comma-separated, in the table's order: stacked, planar, sequential, joint")
      ->default_val(line.variants);
  command->add_option("--threads", options.threads,
                      "Threads of each run (handed to `hsmap run --threads`); 0: every hardware thread")
      ->default_val(options.threads);
  command->add_option("--jobs", options.jobs,
                      "Runs at a time: variants that do not wait for each other's stages run side by side "
                      "(one run leaves about half of a 2-core machine idle, reading and writing files)")
      ->default_val(options.jobs);
  command->add_flag("--force", options.force,
                    "Redo every stage of every run (a shared stage still runs once, in the first variant)");
  return command;
}

int runCompareCommand(CompareCommandLine& line, std::ostream& out, std::ostream& err) {
  try {
    line.options.variants = parseVariantList(line.variants);
  } catch (const std::invalid_argument& failure) {
    err << "error: " << failure.what() << "\n";
    return 1;
  }
  return runCompare(line.options, runThisHsmap, out, err);
}

}  // namespace hsmap
