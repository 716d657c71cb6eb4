// The front-end alone on a survey of your choice, with its timing and, when
// the survey has truth, its frames' shape error:
//   build/benchmarks/frontend_measure_tool SURVEY [--run RUN]
// prints the front-end's summary and the aligned frame error as a percentage
// of the path length (docs/FRONTEND.md, "Measuring"); with --run it also
// writes RUN/frontend/. Under /usr/bin/time -v for its memory.
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <iostream>

#include "core/survey/survey.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"
#include "tests/support/aligned_frame_error.h"

int main(int argc, char** argv) {
  CLI::App app("The front-end alone on a survey: summary, speed, and the aligned frame error against truth/");
  std::filesystem::path folder, run;
  app.add_option("SURVEY", folder, "Survey folder")->required();
  app.add_option("--run", run, "Also write RUN/frontend/");
  CLI11_PARSE(app, argc, argv);
  try {
    const hsmap::Survey survey = hsmap::loadSurvey(folder);
    int last_tenth = -1;
    const auto start = std::chrono::steady_clock::now();
    const hsmap::FrontendResult result =
        hsmap::runFrontend(survey, hsmap::FrontendOptions{}, [&](int done, int total, double fps) {
          const int tenth = 10 * done / total;
          if (tenth != last_tenth) {
            std::cout << "  " << done << "/" << total << " frames, " << fps << " frames/s" << std::endl;
            last_tenth = tenth;
          }
        });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << result.summary() << "\n" << "front-end: " << seconds << " s\n";
    for (const auto& warning : result.warnings) std::cout << "warning: " << warning << "\n";
    if (!run.empty()) hsmap::writeFrontendOutputs(run, result);
    const auto truth_file = folder / "truth" / "rgb_poses.csv";
    if (std::filesystem::exists(truth_file)) {
      const auto truth = hsmap::readTruthPoses(truth_file);
      const hsmap::testing::AlignedError error = hsmap::testing::alignedFrameError(result, truth);
      std::cout << "posed " << result.posedFrameCount() << "/" << result.frames.size() << ", aligned rms "
                << error.rms_m << " m over a " << error.path_length_m << " m path (" << error.percentOfPath()
                << " %), scale " << error.scale << "\n";
    }
  } catch (const std::exception& failure) {
    std::cerr << "error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
