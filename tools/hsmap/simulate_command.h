#pragma once
// `hsmap simulate`: write a synthetic survey with exact ground truth
// (docs/SIMULATOR.md) from a preset or a YAML configuration.
#include <filesystem>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace hsmap {

struct SimulateOptions {
  std::string preset;
  std::filesystem::path config;
  std::filesystem::path out;
  bool force = false;
  bool list_presets = false;
};

CLI::App* addSimulateCommand(CLI::App& app, SimulateOptions& options);
// Returns the exit status; throws InputError for a bad configuration file.
int runSimulateCommand(const SimulateOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
