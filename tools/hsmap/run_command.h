#pragma once
// `hsmap run SURVEY --out RUN [--variant V] [--from STAGE] [--until STAGE]
// [--force] [--threads N] [--log FILE] [stage options]`: the command line of
// the runner (pipelines/run/runner.h, docs/RUN.md). This file only parses:
// the stages, their order and resuming are the runner's.

#include <iosfwd>
#include <string>

#include "pipelines/run/run_options.h"

namespace CLI {
class App;
}

namespace hsmap {

// The command line's texts before they become RunOptions (enums parsed once,
// by runRunCommand).
struct RunCommandLine {
  RunOptions options;
  std::string variant = "sequential";
  std::string surface = "dense";
  std::string joint_tie_points = "strip";
  double seabed_depth_m = 0.0;
  CLI::App* command = nullptr;
};

CLI::App* addRunCommand(CLI::App& app, RunCommandLine& line);
// Exit status as runStages (runner.h): 0, 1 (usage or a stage failed), and
// InputError propagates to main (status 2).
int runRunCommand(RunCommandLine& line, std::ostream& out, std::ostream& err);

}  // namespace hsmap
