// Measurement on a survey of your choice (not part of the normal suite):
//   HSMAP_FRONTEND_SURVEY=/work/surveys/flat [HSMAP_FRONTEND_RUN=/tmp/run] \
//     build/tests/test_frontend --gtest_filter='FrontendMeasure.*'
// runs the front-end, prints its summary and, when the survey has truth, the
// aligned frame error as a percentage of the path length; with
// HSMAP_FRONTEND_RUN it also writes RUN/frontend/.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include "core/survey/survey.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_outputs.h"
#include "pipelines/frontend/frontend_runner.h"
#include "tests/pipelines/frontend/frontend_test_support.h"

namespace hsmap {
namespace {

TEST(FrontendMeasure, SurveyFromTheEnvironment) {
  const char* folder = std::getenv("HSMAP_FRONTEND_SURVEY");
  if (folder == nullptr) GTEST_SKIP() << "set HSMAP_FRONTEND_SURVEY to a survey folder";
  const Survey survey = loadSurvey(folder);
  int last_percent = -1;
  const FrontendResult result = runFrontend(survey, FrontendOptions{}, [&](int done, int total, double fps) {
    const int percent = 100 * done / total;
    if (percent / 10 != last_percent / 10) {
      std::cout << "  " << done << "/" << total << " frames, " << fps << " frames/s" << std::endl;
      last_percent = percent;
    }
  });
  std::cout << result.summary() << "\n";
  for (const auto& warning : result.warnings) std::cout << "warning: " << warning << "\n";
  if (const char* run = std::getenv("HSMAP_FRONTEND_RUN")) writeFrontendOutputs(run, result);
  const auto truth_file = std::filesystem::path(folder) / "truth" / "rgb_poses.csv";
  if (std::filesystem::exists(truth_file)) {
    const auto truth = readTruthPoses(truth_file);
    const testing::AlignedError error = testing::alignedFrameError(result, truth);
    std::cout << "posed " << result.posedFrameCount() << "/" << result.frames.size() << ", aligned rms "
              << error.rms_m << " m over a " << error.path_length_m << " m path (" << error.percentOfPath()
              << " %), scale " << error.scale << "\n";
  }
}

}  // namespace
}  // namespace hsmap
