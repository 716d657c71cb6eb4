#pragma once
// A check before a large write: the products stage knows the size of the
// ortho-image once its grid is set (15.5 GB on a 100 m transect at 5 mm),
// so a file system without room fails at once, with the size and what to
// change, instead of after minutes of casting with "No space left on device".

#include <cstdint>
#include <filesystem>
#include <string>

namespace hsmap {

// Throws std::runtime_error when the file system of `folder` (which must
// exist) has fewer than `bytes` available to this process:
// "<what> needs 15.5 GB in <folder>, which has 2.1 GB free". `what` names
// the output and may say how to shrink it.
void requireFreeSpace(const std::filesystem::path& folder, std::uint64_t bytes, const std::string& what);

}  // namespace hsmap
