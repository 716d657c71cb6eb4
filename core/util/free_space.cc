#include "core/util/free_space.h"

#include <stdexcept>

#include "core/util/message_text.h"

namespace hsmap {

namespace {

std::string gigabytes(std::uint64_t bytes) { return fixedDecimals(double(bytes) / 1e9, 1) + " GB"; }

}  // namespace

void requireFreeSpace(const std::filesystem::path& folder, std::uint64_t bytes, const std::string& what) {
  const std::filesystem::space_info space = std::filesystem::space(folder);
  if (space.available >= bytes) return;
  throw std::runtime_error(what + " needs " + gigabytes(bytes) + " in " + folder.string() + ", which has " +
                           gigabytes(space.available) + " free");
}

}  // namespace hsmap
