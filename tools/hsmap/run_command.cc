#include "tools/hsmap/run_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <ostream>

#include "core/survey/survey.h"
#include "core/util/progress.h"
#include "core/util/stage_timer.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"

namespace hsmap {
namespace {

// The stages in the order they run; `--until` takes one of these.
const std::vector<std::string>& stageNames() {
  static const std::vector<std::string> names = {"frontend"};
  return names;
}

std::string stageList() {
  std::string text;
  for (const auto& name : stageNames()) text += (text.empty() ? "" : ", ") + name;
  return text;
}

// A stage's outputs may be replaced only on purpose.
bool stageFolderUsable(const std::filesystem::path& folder, bool force, std::ostream& err) {
  std::error_code error;
  if (!std::filesystem::exists(folder, error) || force) return true;
  err << "error: " << folder.string()
      << " exists from an earlier run; pass --force to replace that stage's outputs\n";
  return false;
}

void runFrontendStage(const Survey& survey, const RunOptions& options, std::ostream& out) {
  FrontendOptions frontend_options;
  Progress progress("frontend", survey.rgb.frameCount(), "frames", out);
  int reported = 0;
  const FrontendResult result =
      runFrontend(survey, frontend_options, [&](int done, int, double) {
        progress.advance(done - reported);
        reported = done;
      });
  progress.finish();
  writeFrontendOutputs(options.out, result);
  out << result.summary() << "\n";
  for (const auto& warning : result.warnings) out << "warning: " << warning << "\n";
  out << "wrote " << (options.out / "frontend").string()
      << "/ (keyframes, observations, landmarks, frames, frame_stats, losses, segments, "
         "frames.tum)\n";
}

}  // namespace

CLI::App* addRunCommand(CLI::App& app, RunOptions& options) {
  CLI::App* command =
      app.add_subcommand("run", "Run the processing stages on a survey into a run folder");
  command->footer(
      "Stages, in order: " + stageList() +
      " (geo-referencing, surface, joint estimation and the hyperspectral products follow in "
      "later versions). Each stage writes its files into RUN under a temporary name and renames "
      "them when complete; the files are described in docs/SURVEY_FORMAT.md.\n"
      "Exit status: 0 on success; 2 when the survey is invalid (one line naming the file and "
      "the line or key); 1 on other failures.");
  command->add_option("SURVEY", options.survey, "Survey folder (the folder holding survey.yaml)")
      ->required();
  command->add_option("--out", options.out, "Run folder to write into (created if absent)")
      ->required();
  command->add_option("--until", options.until, "Last stage to run: " + stageList())
      ->default_val(options.until);
  command->add_flag("--force", options.force,
                    "Replace the outputs of stages that an earlier run left in RUN");
  return command;
}

int runRunCommand(const RunOptions& options, std::ostream& out, std::ostream& err) {
  bool known = false;
  for (const auto& name : stageNames()) known = known || name == options.until;
  if (!known) {
    err << "error: unknown stage '" << options.until << "' for --until; expected one of "
        << stageList() << "\n";
    return 1;
  }
  std::error_code error;
  if (std::filesystem::exists(options.out, error) &&
      !std::filesystem::is_directory(options.out, error)) {
    err << "error: " << options.out.string() << " exists and is not a folder\n";
    return 1;
  }
  if (!stageFolderUsable(options.out / "frontend", options.force, err)) return 1;
  std::filesystem::create_directories(options.out);

  StageTimings timings;
  auto load_stage = timings.stage("load");
  const Survey survey = loadSurvey(options.survey);
  load_stage.stop();
  out << "survey '" << survey.config.name << "': " << survey.rgb.frameCount() << " RGB frames, "
      << survey.line_times.size() << " scan lines, " << survey.ins.fixes.size() << " INS fixes\n";
  for (const auto& warning : survey.warnings) out << "warning: " << warning << "\n";

  {
    auto frontend_stage = timings.stage("frontend");
    runFrontendStage(survey, options, out);
  }
  out << "stages:";
  for (const auto& [name, seconds] : timings.seconds()) {
    char text[64];
    std::snprintf(text, sizeof(text), " %s %.1f s,", name.c_str(), seconds);
    out << text;
  }
  char total[96];
  std::snprintf(total, sizeof(total), " total %.1f s; peak memory %.0f MiB\n", timings.total(),
                peakResidentMemoryMb());
  out << total;
  return 0;
}

}  // namespace hsmap
