#pragma once
// PositionedFile: a read-only file read at explicit byte offsets (pread), for
// streaming large inputs through a small reused buffer.
//
// Why not only a memory map: touching the pages of a file mapping costs a
// TLB miss and, on virtual machines with shadow or nested paging, a trap per
// 4 KB page; pread copies from the page cache through the kernel's own
// (huge-page) mapping instead, at the speed of `cat`. docs/BENCHMARKS.md
// ("ENVI streaming read") has the measurements.
//
// readAt is thread-safe (pread does not move a shared file position).
// Errors throw InputError naming the file: missing, a directory, unreadable,
// or a read that ends before the requested bytes (file shrunk after opening).

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace hsmap {

class PositionedFile {
 public:
  enum class Access { normal, sequential, random };

  explicit PositionedFile(const std::filesystem::path& path, Access access = Access::normal);
  ~PositionedFile();
  PositionedFile(PositionedFile&& other) noexcept;
  PositionedFile& operator=(PositionedFile&& other) noexcept;
  PositionedFile(const PositionedFile&) = delete;
  PositionedFile& operator=(const PositionedFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::uint64_t size() const { return size_; }

  // Reads exactly `length` bytes at `offset` into `out`.
  void readAt(std::uint64_t offset, std::byte* out, std::size_t length) const;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace hsmap
