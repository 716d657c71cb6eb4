#pragma once
// `hsmap compare SURVEY --out DIR [--variants LIST] [--jobs N] [--threads N] [--force]`:
// the command line of the compare (pipelines/compare/compare_runner.h,
// docs/COMPARE.md). This file only parses; the compare runs the variants as
// child processes of this executable (child_process.h).

#include <iosfwd>
#include <string>

#include "pipelines/compare/compare_runner.h"

namespace CLI {
class App;
}

namespace hsmap {

struct CompareCommandLine {
  CompareOptions options;
  std::string variants = "stacked,planar,sequential,joint";
};

CLI::App* addCompareCommand(CLI::App& app, CompareCommandLine& line);
// Exit status as runCompare: 0, 1 (usage, or a variant failed); InputError
// propagates to main (status 2).
int runCompareCommand(CompareCommandLine& line, std::ostream& out, std::ostream& err);

}  // namespace hsmap
