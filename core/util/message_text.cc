#include "core/util/message_text.h"

#include <cstdio>
#include <ios>
#include <sstream>

namespace hsmap {

std::string fixedDecimals(double value, int decimals) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(decimals);
  text << value;
  return text.str();
}

std::size_t utf8SequenceLength(std::string_view text) {
  if (text.empty()) return 0;
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // allowed range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;   // overlong
    if (lead == 0xED) high = 0x9F;  // UTF-16 surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;   // overlong
    if (lead == 0xF4) high = 0x8F;  // above U+10FFFF
  } else {
    return 0;  // continuation byte, overlong C0/C1, or F5..FF
  }
  if (text.size() < length) return 0;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t i = 2; i < length; ++i) {
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  }
  return length;
}

std::string escapeForMessage(std::string_view text, std::size_t max_chars) {
  std::string out;
  std::size_t printed = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    std::string piece;
    std::size_t consumed = 1;
    switch (c) {
      case '\n': piece = "\\n"; break;
      case '\r': piece = "\\r"; break;
      case '\t': piece = "\\t"; break;
      case '\\': piece = "\\\\"; break;
      default: {
        const std::size_t length = utf8SequenceLength(text.substr(i));
        if (length == 0 || c < 0x20 || c == 0x7F) {
          char hex[8];
          std::snprintf(hex, sizeof(hex), "\\x%02X", c);
          piece = hex;
        } else {
          piece.assign(text.substr(i, length));
          consumed = length;
        }
      }
    }
    // A multi-byte character prints as one column; an escape as its length.
    const std::size_t width = (piece.size() > 1 && piece[0] != '\\') ? 1 : piece.size();
    if (printed + width > max_chars) {
      return out + "... (" + std::to_string(text.size()) + " bytes)";
    }
    out += piece;
    printed += width;
    i += consumed;
  }
  return out;
}

std::string quoteForMessage(std::string_view text, std::size_t max_chars) {
  return "'" + escapeForMessage(text, max_chars) + "'";
}

}  // namespace hsmap
