#pragma once
// Reading a few bytes of a file at an offset, and the big-endian integers of
// image formats (PNG chunk lengths, JPEG segment lengths): shared by the
// image header and integrity checks, which read files without decoding them.
#include <cstddef>
#include <cstdint>

namespace hsmap {

// Reads up to `size` bytes at `offset` of the open descriptor `fd` (pread,
// retried on EINTR); returns how many were read (fewer at the end of file or
// on an error).
std::size_t readBytesAt(int fd, std::uint64_t offset, unsigned char* out, std::size_t size);

inline std::uint32_t bigEndian32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}
inline std::uint32_t bigEndian16(const unsigned char* p) { return (std::uint32_t{p[0]} << 8) | std::uint32_t{p[1]}; }

}  // namespace hsmap
