#include "core/io/image_header.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <string_view>

#include "core/io/file_bytes.h"
#include "core/util/message_text.h"
#include "core/util/regular_file.h"

namespace hsmap {
namespace {

std::optional<ImageHeader> fail(std::string* why, std::string reason) {
  if (why) *why = std::move(reason);
  return std::nullopt;
}

std::optional<ImageHeader> pngHeader(const unsigned char* head, std::size_t size, std::string* why) {
  // Signature (8), IHDR length (4) and type (4), width (4), height (4).
  if (size < 24 || std::string_view(reinterpret_cast<const char*>(head + 12), 4) != "IHDR") {
    return fail(why, "a damaged PNG image (no IHDR chunk after the signature)");
  }
  const std::uint32_t width = bigEndian32(head + 16), height = bigEndian32(head + 20);
  // The PNG specification limits both to 2^31 - 1; zero is invalid.
  if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu) {
    return fail(why, "a damaged PNG image (IHDR gives " + std::to_string(width) + "x" +
                         std::to_string(height) + " pixels)");
  }
  return ImageHeader{"PNG", static_cast<int>(width), static_cast<int>(height)};
}

bool isStartOfFrame(unsigned char marker) {
  // SOF0..SOF15 are C0..CF except C4 (DHT), C8 (JPG extension), CC (DAC).
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

std::optional<ImageHeader> jpegHeader(int fd, std::uint64_t file_size, std::string* why) {
  std::uint64_t at = 2;  // after SOI
  // Each segment is at least 4 bytes, so this bounds the walk on any file.
  while (at + 4 <= file_size) {
    std::array<unsigned char, 9> segment{};
    if (readBytesAt(fd, at, segment.data(), 4) < 4) break;
    if (segment[0] != 0xFF) return fail(why, "a damaged JPEG image (no marker at byte " + std::to_string(at) + ")");
    const unsigned char marker = segment[1];
    if (marker == 0xFF) {  // fill byte before a marker
      at += 1;
      continue;
    }
    if (marker == 0xD9 || marker == 0xDA) break;  // end of image / start of scan before any frame
    const std::uint32_t length = bigEndian16(segment.data() + 2);
    if (length < 2) return fail(why, "a damaged JPEG image (segment length " + std::to_string(length) + ")");
    if (isStartOfFrame(marker)) {
      if (length < 7 || readBytesAt(fd, at + 4, segment.data() + 4, 5) < 5) break;
      const std::uint32_t height = bigEndian16(segment.data() + 5);
      const std::uint32_t width = bigEndian16(segment.data() + 7);
      if (width == 0 || height == 0) {
        return fail(why, "a JPEG image without a fixed size (" + std::to_string(width) + "x" +
                             std::to_string(height) + " in its frame header)");
      }
      return ImageHeader{"JPEG", static_cast<int>(width), static_cast<int>(height)};
    }
    at += 2 + length;
  }
  return fail(why, "a damaged JPEG image (no frame header before the image data ends)");
}

}  // namespace

std::optional<ImageHeader> readImageHeader(const std::filesystem::path& file, std::string* why) {
  const RegularFile input(file);
  if (input.size() == 0) return fail(why, "an empty file");
  std::array<unsigned char, 24> head{};
  const std::size_t size = readBytesAt(input.fd(), 0, head.data(), head.size());
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size >= 8 && std::equal(kPng, kPng + 8, head.begin())) return pngHeader(head.data(), size, why);
  if (size >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) {
    return jpegHeader(input.fd(), input.size(), why);
  }
  const std::string_view start(reinterpret_cast<const char*>(head.data()), std::min<std::size_t>(size, 8));
  return fail(why, "not a PNG or JPEG image (it starts with " + quoteForMessage(start) + ")");
}

}  // namespace hsmap
