#include "core/io/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace hsmap {

std::filesystem::path AtomicFile::partialPathFor(const std::filesystem::path& path) {
  std::filesystem::path partial = path;
  partial += ".partial";
  return partial;
}

AtomicFile::AtomicFile(std::filesystem::path path, Mode mode)
    : path_(std::move(path)), partial_path_(partialPathFor(path_)), mode_(mode) {
  // A partial file left by an earlier crashed run must not pass for ours.
  std::error_code ec;
  std::filesystem::remove(partial_path_, ec);
  if (mode_ == Mode::stream) {
    stream_.open(partial_path_, std::ios::binary | std::ios::trunc);
    if (!stream_) {
      throw std::runtime_error("cannot create " + partial_path_.string() + ": " +
                               std::strerror(errno));
    }
  }
}

AtomicFile::~AtomicFile() { abandon(); }

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : path_(std::move(other.path_)),
      partial_path_(std::move(other.partial_path_)),
      mode_(other.mode_),
      stream_(std::move(other.stream_)),
      committed_(std::exchange(other.committed_, true)) {}

AtomicFile& AtomicFile::operator=(AtomicFile&& other) noexcept {
  if (this != &other) {
    abandon();
    path_ = std::move(other.path_);
    partial_path_ = std::move(other.partial_path_);
    mode_ = other.mode_;
    stream_ = std::move(other.stream_);
    committed_ = std::exchange(other.committed_, true);
  }
  return *this;
}

std::ofstream& AtomicFile::stream() {
  if (mode_ != Mode::stream) {
    throw std::logic_error("AtomicFile " + path_.string() + " was opened by path, not as a stream");
  }
  return stream_;
}

void AtomicFile::commit() {
  if (committed_) throw std::logic_error("AtomicFile " + path_.string() + " committed twice");
  if (mode_ == Mode::stream) {
    stream_.flush();
    const bool written = stream_.good();
    stream_.close();
    if (!written || stream_.fail()) {
      throw std::runtime_error("writing " + partial_path_.string() + " failed");
    }
  } else if (!std::filesystem::is_regular_file(partial_path_)) {
    throw std::runtime_error("expected " + partial_path_.string() +
                             " to have been written, but it does not exist");
  }
  std::error_code ec;
  std::filesystem::rename(partial_path_, path_, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + partial_path_.string() + " to " + path_.string() +
                             ": " + ec.message());
  }
  committed_ = true;
}

void AtomicFile::abandon() noexcept {
  if (committed_) return;
  if (stream_.is_open()) stream_.close();
  std::error_code ec;  // best effort: nothing useful to do if removal fails
  std::filesystem::remove(partial_path_, ec);
  committed_ = true;
}

void writeTextAtomically(const std::filesystem::path& path, const std::string& text) {
  AtomicFile file(path);
  file.stream() << text;
  file.commit();
}

}  // namespace hsmap
