#pragma once
// pristineSample: the built-in sample survey, written once per test program
// into a temporary folder; tests copy it (copyFolder) before damaging it.
#include <filesystem>

#include "pipelines/sample_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap::testing {

inline const std::filesystem::path& pristineSample() {
  static const TempFolder folder("pristine-sample");
  static const std::filesystem::path sample = [] {
    writeSampleSurvey(folder / "sample");
    return folder / "sample";
  }();
  return sample;
}

}  // namespace hsmap::testing
