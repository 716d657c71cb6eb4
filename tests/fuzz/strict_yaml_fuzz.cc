// libFuzzer target: the strict YAML reading of survey.yaml
// (core/survey/survey_config.h on core/survey/strict_yaml_map.h). Every input
// goes to parseSurveyConfigText, which runs parseYamlText (text checks,
// yaml-cpp, the one-document rule) and then every key, type and range check
// of StrictYamlMap on the document. The only acceptable outcomes are a
// parsed configuration or an hsmap::InputError with a one-line message; any
// other exception (a yaml-cpp one escaping, say), a crash, a sanitizer
// report, a hang or a huge allocation is a finding (docs/FUZZING.md).
//
// truth/calibration.yaml is not fuzzed here: its reader
// (core/survey/truth_files.h) has no entry point on text yet, only on a file.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/survey/survey_config.h"
#include "core/util/input_error.h"
#include "tests/fuzz/input_error_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view raw(reinterpret_cast<const char*>(data), size);
  try {
    hsmap::parseSurveyConfigText(raw, "survey.yaml");
  } catch (const hsmap::InputError& error) {
    hsmap::fuzz::checkOneLine(error);
  }
  return 0;
}
