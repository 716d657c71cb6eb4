#include "core/io/positioned_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "core/util/input_error.h"
#include "core/util/regular_file.h"

namespace hsmap {

PositionedFile::PositionedFile(const std::filesystem::path& path, Access access) : path_(path) {
  // RegularFile: a FIFO or a device is an error, never a hang or an endless read.
  RegularFile file(path);
  size_ = file.size();
  fd_ = file.release();
  // A hint for the kernel's read-ahead; failure only changes speed.
  const int advice = access == Access::sequential ? POSIX_FADV_SEQUENTIAL
                     : access == Access::random   ? POSIX_FADV_RANDOM
                                                  : POSIX_FADV_NORMAL;
  ::posix_fadvise(fd_, 0, 0, advice);
}

PositionedFile::~PositionedFile() {
  if (fd_ >= 0) ::close(fd_);
}

PositionedFile::PositionedFile(PositionedFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), size_(std::exchange(other.size_, 0)) {}

PositionedFile& PositionedFile::operator=(PositionedFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

void PositionedFile::readAt(std::uint64_t offset, std::byte* out, std::size_t length) const {
  while (length > 0) {
    const ssize_t got = ::pread(fd_, out, length, static_cast<off_t>(offset));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(path_, "byte " + std::to_string(offset),
                       std::string("read failed: ") + std::strerror(errno));
    }
    if (got == 0) {
      throw InputError(path_, "byte " + std::to_string(offset),
                       "file ended early: expected " + std::to_string(length) + " more bytes");
    }
    out += got;
    length -= static_cast<std::size_t>(got);
    offset += static_cast<std::uint64_t>(got);
  }
}

}  // namespace hsmap
