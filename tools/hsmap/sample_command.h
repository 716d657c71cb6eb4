#pragma once
// `hsmap sample --out DIR`: writes the small built-in sample survey
// (pipelines/sample_survey.h) to DIR. It refuses a DIR that exists and is
// not empty unless --force is given, in which case DIR is replaced whole.

#include <filesystem>
#include <iosfwd>

namespace CLI {
class App;
}

namespace hsmap {

struct SampleOptions {
  std::filesystem::path out;  // folder to write the sample survey into
  bool force = false;         // replace a non-empty `out`
};

CLI::App* addSampleCommand(CLI::App& app, SampleOptions& options);

// Returns the exit status: 0 when written, 1 when `out` is refused (message on `err`).
int runSampleCommand(const SampleOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
