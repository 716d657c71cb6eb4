#pragma once
// The rule shared by the commands that write a whole folder (`sample`,
// `simulate`): --out must be absent, an empty folder, or replaced on purpose
// with --force.
#include <filesystem>
#include <iosfwd>

namespace hsmap {

// True when `out` may be written. Otherwise prints "error: ..." to `err`
// (not a folder; not empty without `force`) and returns false.
bool outputFolderUsable(const std::filesystem::path& out, bool force, std::ostream& err);

}  // namespace hsmap
