#pragma once
// An image for a self-contained HTML page: read, shrunk so that its longer
// side is at most `max_side` pixels (area averaging), encoded as PNG (the
// quick-looks' transparent no-data stays transparent) and written as a
// data: URI, so the page needs no other file and makes no request.

#include <filesystem>
#include <string>
#include <string_view>

namespace hsmap {

// Empty when the file is absent or not an image OpenCV reads.
std::string imageDataUri(const std::filesystem::path& image, int max_side);

// RFC 4648 base64 (with padding).
std::string base64(std::string_view bytes);

}  // namespace hsmap
