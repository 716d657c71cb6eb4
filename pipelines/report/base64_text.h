#pragma once
// Base64 (RFC 4648, with padding): how the report inlines images and the
// spectral grid, as data: URIs and strings, so that the page needs no other file.

#include <string>
#include <string_view>

namespace hsmap {

std::string base64Encode(std::string_view bytes);

}  // namespace hsmap
