#pragma once
// The tiny preset simulated once per test program by the real binary
// (3 s to write), for the tests of `hsmap run` and `hsmap evaluate`.
#include <filesystem>
#include <stdexcept>

#include "tests/support/run_hsmap.h"
#include "tests/support/temp_folder.h"

namespace hsmap::testing {

inline const std::filesystem::path& simulatedTinySurvey() {
  static const TempFolder folder("tools-tiny-survey");
  static const std::filesystem::path survey = [] {
    const std::filesystem::path path = folder / "tiny";
    const RunResult simulate = runHsmap(folder, "simulate --preset tiny --out " + quoted(path.string()));
    if (simulate.exit_status != 0) throw std::runtime_error("simulate failed: " + simulate.err);
    return path;
  }();
  return survey;
}

}  // namespace hsmap::testing
