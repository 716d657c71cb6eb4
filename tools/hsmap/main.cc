// hsmap: one executable, one subcommand per task (COLMAP-style). Errors in
// the user's input (InputError) exit with status 2 and one line
// "error: <file>:<line or key>: <what was expected>" on stderr; any other
// failure exits with status 1.

#include <CLI/CLI.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "core/util/input_error.h"
#include "tools/hsmap/compare_command.h"
#include "tools/hsmap/evaluate_command.h"
#include "tools/hsmap/inspect_command.h"
#include "tools/hsmap/report_command.h"
#include "tools/hsmap/run_command.h"
#include "tools/hsmap/sample_command.h"
#include "tools/hsmap/simulate_command.h"

int main(int argc, char** argv) {
  // hsmap reports problems itself, in one line each; OpenCV's own log lines
  // (e.g. "imread_(...): can't open/read file") would only precede them.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);

  CLI::App app(
      "hsmap: geo-referenced hyperspectral 3D maps from underwater surveys (RGB video, push-broom "
      "hyperspectral camera, INS).",
      "hsmap");
  app.set_version_flag("--version", std::string("hsmap ") + HSMAP_VERSION,
                       "Print the program version and exit");
  app.require_subcommand(1);

  hsmap::InspectOptions inspect_options;
  CLI::App* inspect = hsmap::addInspectCommand(app, inspect_options);
  hsmap::SampleOptions sample_options;
  CLI::App* sample = hsmap::addSampleCommand(app, sample_options);
  hsmap::RunCommandLine run_options;
  CLI::App* run = hsmap::addRunCommand(app, run_options);
  hsmap::SimulateOptions simulate_options;
  CLI::App* simulate = hsmap::addSimulateCommand(app, simulate_options);
  hsmap::EvaluateOptions evaluate_options;
  CLI::App* evaluate = hsmap::addEvaluateCommand(app, evaluate_options);
  hsmap::ReportOptions report_options;
  CLI::App* report = hsmap::addReportCommand(app, report_options);
  hsmap::CompareCommandLine compare_options;
  CLI::App* compare = hsmap::addCompareCommand(app, compare_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0; usage errors are 1.
    return app.exit(e) == 0 ? 0 : 1;
  }

  try {
    if (inspect->parsed()) return hsmap::runInspectCommand(inspect_options, std::cout);
    if (run->parsed()) return hsmap::runRunCommand(run_options, std::cout, std::cerr);
    if (evaluate->parsed()) return hsmap::runEvaluateCommand(evaluate_options, std::cout);
    if (report->parsed()) return hsmap::runReportCommand(report_options, std::cout, std::cerr);
    if (compare->parsed()) return hsmap::runCompareCommand(compare_options, std::cout, std::cerr);
    if (sample->parsed()) return hsmap::runSampleCommand(sample_options, std::cout, std::cerr);
    if (simulate->parsed()) {
      return hsmap::runSimulateCommand(simulate_options, std::cout, std::cerr);
    }
  } catch (const hsmap::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
