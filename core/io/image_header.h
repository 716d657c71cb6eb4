#pragma once
// readImageHeader: the format and pixel size of a PNG or JPEG file, read
// from its first bytes without decoding the image.
//
// Validating a survey must look at every RGB frame (a frame that is empty,
// not an image, of another size, or a stray path such as /etc/passwd would
// otherwise be found only when a later stage decodes it), but decoding 1,200
// full frames takes tens of seconds. The header holds what the check needs:
//   PNG   the 8-byte signature, then the IHDR chunk (width, height: 4-byte
//         big-endian integers at bytes 16 and 20);
//   JPEG  the SOI marker FF D8, then marker segments up to the first
//         start-of-frame (SOF0..SOF15 but DHT, JPG and DAC), whose payload
//         holds height and width (2-byte big-endian); APPn segments (EXIF
//         thumbnails) are skipped by their length, not read.
// A file that is neither, is cut short, or has a zero size is reported by
// `why` in words ("not a PNG or JPEG image (it starts with '#!/bi')").

#include <filesystem>
#include <optional>
#include <string>

namespace hsmap {

struct ImageHeader {
  std::string format;  // "PNG" or "JPEG"
  int width = 0;
  int height = 0;
};

// The header of `file`, or nullopt with *why set to the reason. The file is
// opened as a RegularFile (a FIFO or device is refused, never read); an
// InputError is thrown only when it cannot be opened at all.
std::optional<ImageHeader> readImageHeader(const std::filesystem::path& file, std::string* why);

}  // namespace hsmap
