#pragma once
// What the compare's Markdown and HTML pages say besides the table: which
// survey, where the runs are, and how long the whole compare took.

#include <filesystem>

namespace hsmap {

struct CompareReportContext {
  std::filesystem::path survey;  // absolute
  std::filesystem::path out;     // DIR: the runs are DIR/<variant>
  double wall_time_s = 0.0;      // the whole compare
  bool evaluated = true;         // the survey has truth/
};

}  // namespace hsmap
