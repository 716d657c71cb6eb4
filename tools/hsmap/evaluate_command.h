#pragma once
// `hsmap evaluate RUN --truth SURVEY/truth`: scores a run's results folder
// against a simulated survey's ground truth, writes RUN/metrics.json and
// prints the same figures as a table (docs/EVALUATE.md). Invalid or
// inconsistent input surfaces as InputError, which main() turns into exit
// status 2 with one line naming the file, row or key and what was expected.

#include <filesystem>
#include <iosfwd>

namespace CLI {
class App;
}

namespace hsmap {

struct EvaluateOptions {
  std::filesystem::path run;    // the results folder of `hsmap run ... --out RUN`
  std::filesystem::path truth;  // SURVEY/truth
};

CLI::App* addEvaluateCommand(CLI::App& app, EvaluateOptions& options);

// Returns the exit status (0). Throws InputError for bad input.
int runEvaluateCommand(const EvaluateOptions& options, std::ostream& out);

}  // namespace hsmap
