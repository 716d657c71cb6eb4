#pragma once
// Helpers of the front-end tests: simulated surveys (shared per test
// program, written once into the temp folder); the aligned trajectory
// error against the truth is tests/support/aligned_frame_error.h.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/survey/survey.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/simulate/simulate_survey.h"
#include "tests/support/aligned_frame_error.h"

namespace hsmap::testing {

// Simulates `config` once per test program under a name; removed at exit.
inline std::filesystem::path simulatedFrontendSurvey(const std::string& name, const SimulationConfig& config) {
  static std::map<std::string, std::filesystem::path> made;
  const auto it = made.find(name);
  if (it != made.end()) return it->second;
  const std::filesystem::path folder = std::filesystem::temp_directory_path() /
                                       ("hsmap_frontend_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  std::ostringstream log;
  simulateSurvey(config, folder, log);
  made[name] = folder;
  return folder;
}

struct SimulatedSurveysCleanup {
  ~SimulatedSurveysCleanup() {
    std::error_code ignored;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::temp_directory_path(), ignored)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("hsmap_frontend_", 0) == 0 &&
          name.size() > std::to_string(::getpid()).size() &&
          name.substr(name.size() - std::to_string(::getpid()).size()) == std::to_string(::getpid())) {
        std::filesystem::remove_all(entry.path(), ignored);
      }
    }
  }
};

}  // namespace hsmap::testing
