#pragma once
// Regular input files, opened so that a wrong path can never hang or flood
// the program.
//
// Every survey input is a regular file. A path that names a named pipe
// (FIFO) would block open() until some other process writes to it; one that
// names /dev/zero or /dev/urandom would be read until memory runs out. So
// inputs are opened with O_NONBLOCK (a FIFO then opens at once) and
// fstat()ed on the open descriptor (no race between the check and the
// read), and anything that is not a regular file is an InputError naming
// the file and what it is instead.

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace hsmap {

// Why `file` is not a readable regular file: "not found", "a directory",
// "a named pipe (FIFO)", "a character device", "a block device", "a socket";
// nullopt when it is a regular file (symbolic links are followed).
std::optional<std::string> whyNotRegularFile(const std::filesystem::path& file);

// An open, read-only descriptor of a regular file; closed on destruction.
class RegularFile {
 public:
  // Throws InputError(file, "", "<why>; expected a regular file") or
  // "cannot open the file: <strerror>".
  explicit RegularFile(const std::filesystem::path& file);
  RegularFile(RegularFile&& other) noexcept;
  RegularFile& operator=(RegularFile&&) = delete;
  RegularFile(const RegularFile&) = delete;
  ~RegularFile();

  int fd() const { return fd_; }
  std::uint64_t size() const { return size_; }
  // Hands the descriptor over to the caller, who then closes it.
  int release();

 private:
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace hsmap
