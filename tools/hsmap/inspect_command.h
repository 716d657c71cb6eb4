#pragma once
// `hsmap inspect SURVEY`: loads a survey folder through loadSurvey (every
// file validated, see core/survey/survey.h) and prints its summary. Invalid
// input surfaces as InputError, which main() turns into exit status 2.

#include <filesystem>
#include <iosfwd>

namespace CLI {
class App;
}

namespace hsmap {

struct InspectOptions {
  std::filesystem::path survey;  // the survey folder (holding survey.yaml)
};

// Registers the subcommand on `app`; parsed values land in `options`.
CLI::App* addInspectCommand(CLI::App& app, InspectOptions& options);

// Runs it; returns the exit status (0). Throws InputError for a bad survey.
int runInspectCommand(const InspectOptions& options, std::ostream& out);

}  // namespace hsmap
