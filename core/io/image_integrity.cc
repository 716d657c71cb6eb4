#include "core/io/image_integrity.h"

#include <zlib.h>

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/io/file_bytes.h"
#include "core/util/regular_file.h"

namespace hsmap {
namespace {

// A chunk type as printed: four ASCII letters, or its bytes in hex.
std::string chunkName(const unsigned char* type) {
  std::string name;
  for (int i = 0; i < 4; ++i) {
    const unsigned char c = type[i];
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'))) {
      char hex[16];
      std::snprintf(hex, sizeof(hex), "%02X%02X%02X%02X", type[0], type[1], type[2], type[3]);
      return std::string("0x") + hex;
    }
    name += char(c);
  }
  return name;
}

std::optional<std::string> pngDamage(int fd, std::uint64_t file_size) {
  std::uint64_t at = 8;  // after the signature
  std::vector<unsigned char> data;
  while (true) {
    std::array<unsigned char, 8> head{};
    if (at == file_size) return "truncated: the file ends at byte " + std::to_string(file_size) + " before the IEND chunk";
    if (readBytesAt(fd, at, head.data(), 8) < 8) {
      return "truncated: the file ends at byte " + std::to_string(file_size) + ", inside a chunk header at byte " +
             std::to_string(at);
    }
    const std::uint64_t length = bigEndian32(head.data());
    const std::string name = chunkName(head.data() + 4);
    if (length > 0x7FFFFFFFu) {
      return "damaged: the chunk at byte " + std::to_string(at) + " gives a length of " + std::to_string(length) +
             " bytes (at most 2^31 - 1)";
    }
    if (at + 12 + length > file_size) {
      return "truncated: the file ends at byte " + std::to_string(file_size) + ", inside the " + name +
             " chunk that starts at byte " + std::to_string(at);
    }
    data.resize(std::size_t(length) + 4);
    if (readBytesAt(fd, at + 8, data.data(), data.size()) < data.size()) {
      return "cannot read the " + name + " chunk at byte " + std::to_string(at);
    }
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, head.data() + 4, 4);
    if (length > 0) crc = crc32(crc, data.data(), uInt(length));
    if (std::uint32_t(crc) != bigEndian32(data.data() + length)) {
      return "damaged: the " + name + " chunk at byte " + std::to_string(at) + " fails its CRC";
    }
    at += 12 + length;
    if (name == "IEND") return std::nullopt;
  }
}

std::optional<std::string> jpegDamage(int fd, std::uint64_t file_size) {
  // The last bytes, past any zero padding.
  constexpr std::size_t kTail = 4096;
  const std::uint64_t start = file_size > kTail ? file_size - kTail : 0;
  std::vector<unsigned char> tail(std::size_t(file_size - start));
  if (readBytesAt(fd, start, tail.data(), tail.size()) < tail.size()) return "cannot read the file's end";
  std::size_t end = tail.size();
  while (end > 0 && tail[end - 1] == 0x00) --end;
  if (end >= 2 && tail[end - 2] == 0xFF && tail[end - 1] == 0xD9) return std::nullopt;
  return "truncated: no end-of-image marker (FF D9) at the end of the file (" + std::to_string(file_size) +
         " bytes)";
}

}  // namespace

std::optional<std::string> findImageDamage(const std::filesystem::path& file) {
  const RegularFile input(file);
  if (input.size() == 0) return "an empty file";
  std::array<unsigned char, 8> head{};
  const std::size_t size = readBytesAt(input.fd(), 0, head.data(), head.size());
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size == 8 && std::equal(kPng, kPng + 8, head.begin())) return pngDamage(input.fd(), input.size());
  if (size >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) return jpegDamage(input.fd(), input.size());
  return "not a PNG or JPEG image";
}

}  // namespace hsmap
