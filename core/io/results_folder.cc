#include "core/io/results_folder.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace hsmap {
namespace {

void createFolders(const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw std::runtime_error("cannot create folder " + folder.string() + ": " + ec.message());
}

}  // namespace

ResultsFolder::ResultsFolder(std::filesystem::path root) : root_(std::move(root)) {
  createFolders(root_);
}

std::filesystem::path ResultsFolder::prepare(const std::filesystem::path& relative_path) const {
  if (relative_path.empty() || relative_path.is_absolute()) {
    throw std::invalid_argument("results product path must be relative, got '" +
                                relative_path.string() + "'");
  }
  for (const auto& part : relative_path) {
    if (part == "..") {
      throw std::invalid_argument("results product path must stay inside the folder, got '" +
                                  relative_path.string() + "'");
    }
  }
  const std::filesystem::path full = root_ / relative_path;
  createFolders(full.parent_path());
  return full;
}

AtomicFile ResultsFolder::product(const std::filesystem::path& relative_path,
                                  AtomicFile::Mode mode) const {
  return AtomicFile(prepare(relative_path), mode);
}

}  // namespace hsmap
