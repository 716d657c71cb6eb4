#pragma once
// Small text inputs (YAML, CSV, ENVI headers): read with a size limit, then
// checked and normalised before any parser sees them.
//
// readTextFile() opens the file as a RegularFile (regular_file.h: a FIFO or
// a device is an error, never a hang) and refuses a file larger than
// `max_bytes` before reading it, so a wrong path can not exhaust memory.
//
// normaliseText() is what every text parser runs first (it is separate from
// reading so that parsers of in-memory text, and the fuzz targets, go
// through the same checks):
//   - a UTF-8 byte-order mark at the start is dropped;
//   - line ends CRLF and CR alone (old Mac files) become LF, so line numbers
//     in messages match what an editor shows whatever wrote the file;
//   - a NUL or another control character (except tab) is an error at its
//     line: it means a binary or damaged file, and a NUL would silently cut a
//     file name handed to the operating system;
//   - with TextEncoding::utf8, bytes that are not UTF-8 are an error at their
//     line (text values are printed back to users and written to products).
//     ENVI headers are read with TextEncoding::any_bytes: headers written by
//     older tools may hold Latin-1 in their description, which hsmap keeps
//     verbatim and only ever prints escaped.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace hsmap {

enum class TextEncoding { utf8, any_bytes };

// Size limits of the text inputs, generous for real surveys (a 10-hour
// 200 Hz INS log is ~0.4 GB of CSV; a header with thousands of bands ~0.1 MB).
inline constexpr std::uint64_t kMaxYamlBytes = 1ull << 20;        // 1 MiB
inline constexpr std::uint64_t kMaxEnviHeaderBytes = 16ull << 20; // 16 MiB
inline constexpr std::uint64_t kMaxCsvBytes = 1ull << 30;         // 1 GiB

// The raw bytes of `file`. InputError naming the file when it is not a
// regular file, is larger than `max_bytes` ("is 2.1 GB; expected a text file
// of at most 1.0 GB") or cannot be read.
std::string readTextFile(const std::filesystem::path& file, std::uint64_t max_bytes);

// The checks and normalisation above; errors are InputError(file, "line N", ...).
std::string normaliseText(std::string_view raw, const std::filesystem::path& file,
                          TextEncoding encoding);

}  // namespace hsmap
