#pragma once
// MappedFile: a read-only memory map of a whole file, for streaming large
// inputs (the UHI cube is gigabytes) without reading them into the heap.
//
// Contract
// - The mapping is private and read-only; data() is valid for size() bytes
//   while the object lives (an empty file maps to data() == nullptr, size 0).
// - advise() passes an access-pattern hint (madvise) for the whole file or a
//   range: `sequential` asks the kernel for aggressive read-ahead, `willNeed`
//   starts reading a range in the background.
// - release(offset, length) drops the pages lying wholly inside the range from
//   this process (MADV_DONTNEED). For a file mapping this only unmaps them:
//   the page cache keeps them, and reading the range again faults them back
//   in with the same content. Streaming readers call it on the bytes behind
//   their cursor so that the resident set stays small, since pages of a file
//   mapping count in RSS for as long as they are mapped.
// - Errors (missing file, directory, unreadable, mmap failure) throw
//   InputError naming the file.

#include <cstddef>
#include <filesystem>

namespace hsmap {

class MappedFile {
 public:
  enum class Access { normal, sequential, random };

  explicit MappedFile(const std::filesystem::path& path, Access access = Access::normal);
  ~MappedFile();
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const std::byte* data() const { return data_; }
  std::size_t size() const { return size_; }

  // Access-pattern hint for the whole mapping.
  void advise(Access access) const;
  // Starts reading [offset, offset + length) into the page cache in the background.
  void willNeed(std::size_t offset, std::size_t length) const;
  // Drops the whole pages inside [offset, offset + length) from the process;
  // partial pages at either end stay mapped. Const: the visible content does
  // not change.
  void release(std::size_t offset, std::size_t length) const;

 private:
  void unmap() noexcept;

  std::filesystem::path path_;
  std::byte* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace hsmap
