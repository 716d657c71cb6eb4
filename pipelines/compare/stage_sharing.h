#pragma once
// Gives a run folder a stage that another run folder of the same survey has
// finished (compare_plan.h): the stage's files are hard-linked (copied where
// the file system refuses links) into the recipient, then its record
// (RUN/stages/<stage>.yaml) is copied, last, so a stage half shared is never
// up to date. `hsmap run` in the recipient then checks the record as any
// other and skips the stage. Whatever the recipient held of that stage goes
// first. Stages never modify their files in place (they write under
// temporary names and rename), so the two folders can share them.

#include <filesystem>
#include <string>

#include "pipelines/run/stage_table.h"

namespace hsmap {

// False, with `why`, when the donor has no record of the stage (it did not
// finish there); throws std::filesystem_error on I/O.
bool shareStage(const std::filesystem::path& donor, const std::filesystem::path& recipient, StageId stage,
                std::string& why);

}  // namespace hsmap
