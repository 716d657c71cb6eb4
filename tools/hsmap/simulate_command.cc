#include "tools/hsmap/simulate_command.h"
#include "tools/hsmap/output_folder.h"

#include <CLI/CLI.hpp>
#include <ostream>

#include "pipelines/simulate/simulate_survey.h"
#include "pipelines/simulate/simulation_config_yaml.h"

namespace hsmap {
namespace {
std::string presetList() {
  std::string text;
  for (const std::string& name : simulationPresetNames()) text += (text.empty() ? "" : ", ") + name;
  return text;
}
}  // namespace

CLI::App* addSimulateCommand(CLI::App& app, SimulateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "simulate", "Write a synthetic survey with exact ground truth (truth/) to a folder");
  command->footer(
      "Presets: " + presetList() +
      ". A --config file names a preset and overrides any of its settings; every setting is "
      "documented in docs/SIMULATOR.md. The same preset or configuration (and seed) writes the "
      "same bytes.");
  auto* preset = command->add_option("--preset", options.preset, "Preset to simulate: " + presetList());
  auto* config = command->add_option("--config", options.config,
                                     "YAML file (format: hsmap-simulation/1) with a preset and "
                                     "the settings that differ from it");
  preset->excludes(config);
  config->excludes(preset);
  command->add_option("--out", options.out,
                      "Folder to write the survey into; it must be empty or absent unless "
                      "--force is given");
  command->add_flag("--force", options.force,
                    "Replace --out even if it is not empty: its previous contents are deleted");
  command->add_flag("--list-presets", options.list_presets, "List the presets and exit");
  return command;
}

int runSimulateCommand(const SimulateOptions& options, std::ostream& out, std::ostream& err) {
  if (options.list_presets) {
    for (const std::string& name : simulationPresetNames()) out << name << "\n";
    return 0;
  }
  if (options.preset.empty() && options.config.empty()) {
    err << "error: give --preset NAME or --config FILE.yaml (presets: " << presetList() << ")\n";
    return 1;
  }
  if (options.out.empty()) {
    err << "error: --out is required\n";
    return 1;
  }
  SimulationConfig config;
  if (!options.preset.empty()) {
    const auto preset = simulationPreset(options.preset);
    if (!preset) {
      err << "error: unknown preset '" << options.preset << "'; expected one of " << presetList()
          << "\n";
      return 1;
    }
    config = *preset;
  } else {
    config = readSimulationConfig(options.config);
  }
  if (!outputFolderUsable(options.out, options.force, err)) return 1;
  out << "simulating '" << config.name << "' (preset " << config.preset << ", seed " << config.seed
      << ")" << std::endl;
  const SimulationSummary summary = simulateSurvey(config, options.out, out);
  out << summary.toString();
  out << "check it with: hsmap inspect " << summary.folder.string() << "\n";
  return 0;
}

}  // namespace hsmap
