#pragma once
// runHsmap: runs the built `hsmap` executable (HSMAP_TOOL_PATH) as a user
// would, with stdout and stderr captured, for the tests of the command line.
#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "tests/support/temp_folder.h"

namespace hsmap::testing {

struct RunResult {
  int exit_status = -1;
  std::string out;
  std::string err;
};

// `text` as one shell word.
inline std::string quoted(const std::string& text) {
  std::string result = "'";
  for (char c : text) result += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return result + "'";
}

// Runs `hsmap <arguments>` with stdout and stderr captured in files of
// `temp`. Under `timeout`, so that a regression that blocks (e.g. on a FIFO)
// fails the test instead of hanging the suite: exit status 124 then.
inline RunResult runHsmap(const TempFolder& temp, const std::string& arguments,
                          int timeout_s = 120) {
  const auto out = temp / "stdout.txt";
  const auto err = temp / "stderr.txt";
  const std::string command = "timeout " + std::to_string(timeout_s) + " " +
                              quoted(HSMAP_TOOL_PATH) + " " + arguments + " >" +
                              quoted(out.string()) + " 2>" + quoted(err.string());
  const int status = std::system(command.c_str());
  RunResult result;
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = readText(out);
  result.err = readText(err);
  return result;
}

}  // namespace hsmap::testing
