#include "tools/hsmap/output_folder.h"

#include <ostream>
#include <system_error>

namespace hsmap {

bool outputFolderUsable(const std::filesystem::path& out, bool force, std::ostream& err) {
  std::error_code error;
  if (!std::filesystem::exists(out, error)) return true;
  if (!std::filesystem::is_directory(out, error)) {
    err << "error: " << out.string() << " exists and is not a folder\n";
    return false;
  }
  if (!std::filesystem::is_empty(out, error) && !force) {
    err << "error: " << out.string()
        << " is not empty; pass --force to replace it (its contents will be deleted)\n";
    return false;
  }
  return true;
}

}  // namespace hsmap
