#include "core/io/published_file.h"

#include <system_error>

#include "core/io/atomic_file.h"

namespace hsmap {

namespace fs = std::filesystem;

void publishFile(const fs::path& from, const fs::path& to) {
  if (to.has_parent_path()) fs::create_directories(to.parent_path());
  const fs::path partial = AtomicFile::partialPathFor(to);
  fs::remove(partial);
  std::error_code refused;
  fs::create_hard_link(from, partial, refused);
  if (refused) fs::copy_file(from, partial, fs::copy_options::overwrite_existing);
  fs::rename(partial, to);
}

}  // namespace hsmap
