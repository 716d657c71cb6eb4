#pragma once
// `hsmap run SURVEY --out RUN [--until STAGE]`: the stages of a run, in
// order, each writing its files into the run folder (docs/SURVEY_FORMAT.md).
// The stages in place so far: frontend (the monocular visual front-end,
// docs/FRONTEND.md). Geo-referencing, surface, joint estimation and the
// hyperspectral products follow as they land; --until names the last stage
// to run.
#include <filesystem>
#include <iosfwd>
#include <string>

namespace CLI {
class App;
}

namespace hsmap {

struct RunOptions {
  std::filesystem::path survey;
  std::filesystem::path out;
  std::string until = "frontend";
  bool force = false;
};

CLI::App* addRunCommand(CLI::App& app, RunOptions& options);
// Exit status: 0 on success, 1 for a usage error or a stage that fails
// (reported on `err`); InputError (bad survey) propagates to main (status 2).
int runRunCommand(const RunOptions& options, std::ostream& out, std::ostream& err);

}  // namespace hsmap
