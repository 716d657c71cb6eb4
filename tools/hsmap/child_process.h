#pragma once
// Runs this hsmap executable again as a child process, for `hsmap compare`
// (pipelines/compare/compare_runner.h): each variant's run is a process of
// its own, so that its time and peak memory are its own and a crash ends
// only that variant.

#include <string>
#include <vector>

#include "pipelines/compare/compare_runner.h"

namespace hsmap {

// `/proc/self/exe <arguments>`, with stdout and stderr merged into one pipe
// handed to `output` as it comes. Returns the exit status, 128 + the signal's
// number when a signal ended it; throws std::system_error when the process
// cannot be started.
int runThisHsmap(const std::vector<std::string>& arguments, const HsmapOutput& output);

}  // namespace hsmap
