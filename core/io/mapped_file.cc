#include "core/io/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>
#include <utility>

#include "core/util/input_error.h"
#include "core/util/regular_file.h"

namespace hsmap {
namespace {

int adviceFor(MappedFile::Access access) {
  switch (access) {
    case MappedFile::Access::sequential: return MADV_SEQUENTIAL;
    case MappedFile::Access::random: return MADV_RANDOM;
    case MappedFile::Access::normal: break;
  }
  return MADV_NORMAL;
}

std::size_t pageSize() {
  static const std::size_t size = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return size;
}

// Closes the descriptor on every path out of the constructor: the mapping
// keeps the file alive on its own.
struct FdGuard {
  int fd;
  ~FdGuard() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

MappedFile::MappedFile(const std::filesystem::path& path, Access access) : path_(path) {
  // RegularFile: a FIFO or a device is an error, never a hang or an endless read.
  RegularFile file(path);
  const FdGuard fd{file.release()};
  size_ = static_cast<std::size_t>(file.size());
  if (size_ == 0) return;  // mmap refuses empty lengths; an empty map is valid
  void* address = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd.fd, 0);
  if (address == MAP_FAILED) {
    size_ = 0;
    throw InputError(path, "", std::string("cannot memory-map: ") + std::strerror(errno));
  }
  data_ = static_cast<std::byte*>(address);
  advise(access);
}

MappedFile::~MappedFile() { unmap(); }

MappedFile::MappedFile(MappedFile&& other) noexcept
    : path_(std::move(other.path_)),
      data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
  if (this != &other) {
    unmap();
    path_ = std::move(other.path_);
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
  }
  return *this;
}

void MappedFile::unmap() noexcept {
  if (data_ != nullptr) ::munmap(data_, size_);
  data_ = nullptr;
  size_ = 0;
}

void MappedFile::advise(Access access) const {
  // A hint: failure changes speed, never results, so it is not an error.
  if (data_ != nullptr) ::madvise(data_, size_, adviceFor(access));
}

void MappedFile::willNeed(std::size_t offset, std::size_t length) const {
  if (data_ == nullptr || offset >= size_) return;
  length = std::min(length, size_ - offset);
  const std::size_t page = pageSize();
  const std::size_t begin = offset / page * page;  // willNeed may round outwards
  ::madvise(data_ + begin, offset + length - begin, MADV_WILLNEED);
}

void MappedFile::release(std::size_t offset, std::size_t length) const {
  if (data_ == nullptr || offset >= size_) return;
  length = std::min(length, size_ - offset);
  const std::size_t page = pageSize();
  // Only whole pages: a partial page may hold bytes the caller still needs.
  const std::size_t begin = (offset + page - 1) / page * page;
  std::size_t end = (offset + length) / page * page;
  // The last page of the file may be partial; it is wholly inside the range
  // when the range reaches the end of the file.
  if (offset + length == size_) end = size_;
  if (end <= begin) return;
  ::madvise(data_ + begin, end - begin, MADV_DONTNEED);
}

}  // namespace hsmap
