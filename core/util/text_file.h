#pragma once
// readTextFile: the whole content of a small text input file (YAML, CSV,
// headers), with an InputError naming the file when it cannot be read.
// Large binary data (cubes) is streamed instead, never read this way.

#include <filesystem>
#include <string>

namespace hsmap {

std::string readTextFile(const std::filesystem::path& file);

}  // namespace hsmap
