#include "core/util/text_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "core/util/regular_file.h"

namespace hsmap {
namespace {

std::string sizeText(std::uint64_t bytes) {
  char text[32];
  if (bytes >= (1ull << 30)) {
    std::snprintf(text, sizeof(text), "%.1f GiB", static_cast<double>(bytes) / (1ull << 30));
  } else if (bytes >= (1ull << 20)) {
    std::snprintf(text, sizeof(text), "%.1f MiB", static_cast<double>(bytes) / (1ull << 20));
  } else {
    std::snprintf(text, sizeof(text), "%llu bytes", static_cast<unsigned long long>(bytes));
  }
  return text;
}

std::string byteText(unsigned char c) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%02X", c);
  return text;
}

}  // namespace

std::string readTextFile(const std::filesystem::path& file, std::uint64_t max_bytes) {
  const RegularFile input(file);
  if (input.size() > max_bytes) {
    throw InputError(file, "",
                     "the file is " + sizeText(input.size()) + "; expected a text file of at most " +
                         sizeText(max_bytes));
  }
  std::string text;
  text.resize(static_cast<std::size_t>(input.size()));
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t got = ::read(input.fd(), text.data() + done, text.size() - done);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(file, "", std::string("read error: ") + std::strerror(errno));
    }
    if (got == 0) break;  // the file shrank while being read
    done += static_cast<std::size_t>(got);
  }
  text.resize(done);
  return text;
}

std::string normaliseText(std::string_view raw, const std::filesystem::path& file,
                          TextEncoding encoding) {
  if (raw.substr(0, 3) == "\xEF\xBB\xBF") raw.remove_prefix(3);  // UTF-8 byte-order mark
  std::string text;
  text.reserve(raw.size());
  long long line = 1;
  std::size_t line_start = 0;  // in `text`
  for (std::size_t i = 0; i < raw.size();) {
    const unsigned char c = static_cast<unsigned char>(raw[i]);
    if (c == '\r' || c == '\n') {
      // CRLF, CR and LF all end one line.
      i += (c == '\r' && i + 1 < raw.size() && raw[i + 1] == '\n') ? 2 : 1;
      text += '\n';
      ++line;
      line_start = text.size();
      continue;
    }
    const std::size_t column = text.size() - line_start + 1;
    if ((c < 0x20 && c != '\t') || c == 0x7F) {
      throw InputError(file, InputError::atLine(line),
                       "control character " + byteText(c) + (c == 0 ? " (NUL)" : "") +
                           " in column " + std::to_string(column) +
                           "; expected text (is this a binary or damaged file?)");
    }
    std::size_t length = 1;
    if (c >= 0x80 && encoding == TextEncoding::utf8) {
      length = utf8SequenceLength(raw.substr(i));
      if (length == 0) {
        throw InputError(file, InputError::atLine(line),
                         "byte " + byteText(c) + " in column " + std::to_string(column) +
                             " is not UTF-8; expected UTF-8 text");
      }
    }
    text.append(raw.substr(i, length));
    i += length;
  }
  return text;
}

}  // namespace hsmap
