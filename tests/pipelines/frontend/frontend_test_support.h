#pragma once
// Helpers of the front-end tests: simulated surveys (shared per test
// program, written once into the temp folder) and the aligned trajectory
// error against the truth.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/sim3.h"
#include "core/survey/survey.h"
#include "core/survey/truth_files.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/simulate/simulate_survey.h"

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

struct AlignedError {
  int pairs = 0;
  double rms_m = 0.0;
  double path_length_m = 0.0;
  double scale = 1.0;
  double percentOfPath() const { return path_length_m > 0.0 ? 100.0 * rms_m / path_length_m : 0.0; }
};

// Sim(3) alignment (Umeyama) of the posed frames' positions onto the truth.
inline AlignedError alignedFrameError(const FrontendResult& result, const std::vector<TruthPose>& truth) {
  std::vector<Eigen::Vector3d> source, target;
  for (const FrameRecord& frame : result.frames) {
    if (!frame.posed) continue;
    source.push_back(frame.T_F_C.t);
    target.push_back(truth.at(std::size_t(frame.index)).T_W_X.t);
  }
  AlignedError error;
  error.pairs = int(source.size());
  for (std::size_t i = 1; i < truth.size(); ++i) error.path_length_m += (truth[i].T_W_X.t - truth[i - 1].T_W_X.t).norm();
  if (source.size() < 3) return error;
  const Sim3 S = alignUmeyama(source, target, true);
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) sum_sq += (S.apply(source[i]) - target[i]).squaredNorm();
  error.rms_m = std::sqrt(sum_sq / double(source.size()));
  error.scale = S.scale();
  return error;
}

}  // namespace hsmap::testing
