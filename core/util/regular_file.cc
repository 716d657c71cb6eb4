#include "core/util/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

std::optional<std::string> whyNotRegular(mode_t mode) {
  if (S_ISREG(mode)) return std::nullopt;
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe (FIFO)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string notRegularMessage(const std::string& why) {
  return "is " + why + "; expected a regular file";
}

}  // namespace

std::optional<std::string> whyNotRegularFile(const std::filesystem::path& file) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) return "not found";
    return std::string("not accessible (") + std::strerror(errno) + ")";
  }
  return whyNotRegular(st.st_mode);
}

RegularFile::RegularFile(const std::filesystem::path& file) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer. It changes nothing
  // for the regular files that pass the check below.
  fd_ = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) {
    const int error = errno;
    if (error == ENOENT || error == ENOTDIR) throw InputError(file, "", "file not found");
    throw InputError(file, "", std::string("cannot open the file: ") + std::strerror(error));
  }
  struct stat st {};
  if (::fstat(fd_, &st) != 0) {
    const int error = errno;
    ::close(fd_);
    throw InputError(file, "", std::string("cannot read the file's status: ") +
                                   std::strerror(error));
  }
  if (const auto why = whyNotRegular(st.st_mode)) {
    ::close(fd_);
    throw InputError(file, "", notRegularMessage(*why));
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

RegularFile::RegularFile(RegularFile&& other) noexcept
    : fd_(other.fd_), size_(other.size_) {
  other.fd_ = -1;
}

RegularFile::~RegularFile() {
  if (fd_ >= 0) ::close(fd_);
}

int RegularFile::release() {
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

}  // namespace hsmap
