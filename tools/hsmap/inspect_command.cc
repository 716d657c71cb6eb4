#include "tools/hsmap/inspect_command.h"

#include <CLI/CLI.hpp>
#include <ostream>

#include "core/survey/survey.h"
#include "core/survey/survey_summary.h"

namespace hsmap {

CLI::App* addInspectCommand(CLI::App& app, InspectOptions& options) {
  CLI::App* command =
      app.add_subcommand("inspect", "Validate a survey folder and print its summary");
  command->footer(
      "Loads every file of the survey (survey.yaml, RGB frames or video, UHI cube and lines.csv, "
      "INS) with the same strict checks as every other command and prints the sensors, the time "
      "span, rate and gaps of each stream, the band wavelengths, the origin and whether ground "
      "truth is present.\n"
      "Exit status: 0 when the survey is valid; 2 when it is not, with one line on stderr naming "
      "the file, the line or YAML key, and what was expected; 1 on other failures.");
  command
      ->add_option("SURVEY", options.survey,
                   "Survey folder: the folder holding survey.yaml (format: docs/SURVEY_FORMAT.md / "
                   "docs/SURVEY_FORMAT.md)")
      ->required();
  return command;
}

int runInspectCommand(const InspectOptions& options, std::ostream& out) {
  const Survey survey = loadSurvey(options.survey);
  printSurveySummary(out, summarizeSurvey(survey));
  return 0;
}

}  // namespace hsmap
