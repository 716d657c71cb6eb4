#pragma once
// The `tiny` preset simulated once per test program into a temporary folder,
// shared by the tests that check its ground truth.
#include <filesystem>
#include <sstream>
#include <string>

#include <unistd.h>

#include "pipelines/simulate/simulate_survey.h"

namespace hsmap::testing {

struct TinySurvey {
  SimulationConfig config;
  SimulationSummary summary;
  std::filesystem::path folder;
};

inline const TinySurvey& tinySurvey() {
  static const TinySurvey survey = [] {
    TinySurvey s;
    s.config = *simulationPreset("tiny");
    s.folder = std::filesystem::temp_directory_path() /
               ("hsmap_tiny_survey_" + std::to_string(::getpid()));
    std::ostringstream log;
    s.summary = simulateSurvey(s.config, s.folder, log);
    return s;
  }();
  return survey;
}

// Removes the shared survey when the test program ends.
struct TinySurveyCleanup {
  ~TinySurveyCleanup() {
    std::error_code ignored;
    std::filesystem::remove_all(std::filesystem::temp_directory_path() /
                                    ("hsmap_tiny_survey_" + std::to_string(::getpid())),
                                ignored);
  }
};

}  // namespace hsmap::testing
