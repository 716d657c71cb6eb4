// libFuzzer target: the survey's CSV tables (core/survey/csv_table.h). Every
// input goes to the three table readers (rgb/frames.csv, uhi/lines.csv,
// nav/ins.csv) and to the generic table reader with a truth-pose header, whose
// cells are then read as numbers and integers. The only acceptable outcomes
// are a parsed table or an hsmap::InputError with a one-line message; any
// other exception, a crash, a sanitizer report, a hang or a huge allocation
// is a finding (docs/FUZZING.md).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/survey/csv_table.h"
#include "core/util/input_error.h"
#include "tests/fuzz/input_error_check.h"

namespace {

// Runs `parse`; an InputError is the expected outcome for most inputs.
template <typename Parse>
void expectOnlyInputError(Parse&& parse) {
  try {
    parse();
  } catch (const hsmap::InputError& error) {
    hsmap::fuzz::checkOneLine(error);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view raw(reinterpret_cast<const char*>(data), size);
  expectOnlyInputError([&] { hsmap::parseFramesCsv(raw, "rgb/frames.csv"); });
  expectOnlyInputError([&] { hsmap::parseLinesCsv(raw, "uhi/lines.csv"); });
  expectOnlyInputError([&] { hsmap::parseInsCsv(raw, "nav/ins.csv"); });
  expectOnlyInputError([&] {
    static const std::vector<std::vector<std::string>> kHeaders = {
        {"t", "x", "y", "z", "qw", "qx", "qy", "qz"},
        {"line", "t", "x", "y", "z", "qw", "qx", "qy", "qz"}};
    const hsmap::CsvTable table = hsmap::parseCsvTable(raw, "truth/poses.csv", kHeaders);
    for (const hsmap::CsvTable::Row& row : table.rows) {
      for (std::size_t column = 0; column < table.columns.size(); ++column) {
        expectOnlyInputError([&] { table.number(row, column); });
        expectOnlyInputError([&] { table.integer(row, column); });
      }
    }
  });
  return 0;
}
