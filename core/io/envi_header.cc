#include "core/io/envi_header.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "core/io/atomic_file.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "core/util/text_file.h"

namespace hsmap {
namespace {

constexpr const char* kDataTypeChoices =
    "one of 1, 2, 3, 4, 5, 12, 13 (uint8, int16, int32, float32, float64, uint16, uint32)";

bool isBlank(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string_view trim(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

std::string lowercase(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// `Data  Type` -> `data type`: ENVI keys are case-insensitive and tools differ
// in how they space them.
std::string normaliseKey(std::string_view key) {
  std::string out;
  bool pending_blank = false;
  for (char c : trim(key)) {
    if (isBlank(c)) {
      pending_blank = true;
      continue;
    }
    if (pending_blank) out += ' ';
    pending_blank = false;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

// One `key = value` of the header, with the line it starts on (1-based).
struct Field {
  std::string key_text;  // as written (trimmed)
  std::string value;     // as written (trimmed), braces included, lines joined by '\n'
  long long line = 0;
};

class HeaderParser {
 public:
  explicit HeaderParser(const std::filesystem::path& path) : path_(path) {}

  [[noreturn]] void failAt(long long line, const std::string& detail) const {
    throw InputError(path_, InputError::atLine(line), detail);
  }
  [[noreturn]] void failField(const Field& field, const std::string& detail) const {
    failAt(field.line, "key " + quoteForMessage(normaliseKey(field.key_text), 40) + ": " + detail);
  }

  // Splits the text into fields and comments; checks the magic line.
  void tokenise(const std::string& text, std::vector<std::string>& comments) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines.push_back(std::move(line));
    }
    const std::string first = lines.empty() ? std::string() : std::string(trim(lines[0]));
    if (first != "ENVI") failAt(1, "expected 'ENVI' on line 1, found " + quoteForMessage(first));

    for (std::size_t i = 1; i < lines.size(); ++i) {
      const long long line_number = static_cast<long long>(i) + 1;
      const std::string_view line = trim(lines[i]);
      if (line.empty()) continue;
      if (line.front() == ';') {
        comments.emplace_back(trim(line.substr(1)));
        continue;
      }
      const std::size_t equals = line.find('=');
      if (equals == std::string_view::npos) {
        failAt(line_number, "expected 'key = value' or a ';' comment, found " + quoteForMessage(line));
      }
      Field field;
      field.key_text = std::string(trim(line.substr(0, equals)));
      field.line = line_number;
      if (field.key_text.empty()) failAt(line_number, "expected a key before '='");
      std::string value(trim(line.substr(equals + 1)));
      if (!value.empty() && value.front() == '{') {
        // A braced value runs to the first '}', possibly lines later.
        while (value.find('}') == std::string::npos) {
          if (++i == lines.size()) {
            failField(field, "'{' opened on this line is never closed by '}'");
          }
          // Continuation lines are kept as written: a description or an
          // unknown key's value must round-trip unchanged.
          value += '\n';
          value += lines[i];
        }
        value = std::string(trim(value));
        const std::size_t close = value.find('}');
        if (!trim(std::string_view(value).substr(close + 1)).empty()) {
          failAt(static_cast<long long>(i) + 1,
                 "key " + quoteForMessage(normaliseKey(field.key_text), 40) +
                     ": unexpected text after '}': " +
                     quoteForMessage(trim(std::string_view(value).substr(close + 1))));
        }
      }
      field.value = std::move(value);
      const std::string key = normaliseKey(field.key_text);
      const auto [it, inserted] = index_.emplace(key, fields_.size());
      if (!inserted) {
        failAt(line_number, "key " + quoteForMessage(key, 40) + " appears twice (first on line " +
                                std::to_string(fields_[it->second].line) + ")");
      }
      fields_.push_back(std::move(field));
    }
  }

  const std::vector<Field>& fields() const { return fields_; }

  const Field* find(const std::string& key) const {
    const auto it = index_.find(key);
    return it == index_.end() ? nullptr : &fields_[it->second];
  }

  const Field& require(const std::string& key) const {
    const Field* field = find(key);
    if (field == nullptr) throw InputError(path_, InputError::atKey(key), "required key is missing");
    return *field;
  }

  // The text inside `{ }` (trimmed), or the value itself when it has none.
  static std::string_view inner(const Field& field) {
    std::string_view value = field.value;
    if (!value.empty() && value.front() == '{') {
      value.remove_prefix(1);
      value = value.substr(0, value.find('}'));
    }
    return trim(value);
  }

  std::vector<std::string_view> listItems(const Field& field) const {
    if (field.value.empty() || field.value.front() != '{') {
      failField(field, "expected a list in braces '{ ... }', found " + quoteForMessage(field.value));
    }
    std::vector<std::string_view> items;
    std::string_view rest = inner(field);
    if (rest.empty()) return items;
    while (true) {
      const std::size_t comma = rest.find(',');
      items.push_back(trim(rest.substr(0, comma)));
      if (items.back().empty()) failField(field, "empty item in list (item " + std::to_string(items.size()) + ")");
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    return items;
  }

  template <typename Integer>
  static bool parseInteger(std::string_view text, Integer& value) {
    text = trim(text);
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size() && !text.empty();
  }

  // A finite number: from_chars also reads "nan" and "inf", which no header
  // quantity (wavelength, width, map position) can be.
  static bool parseDouble(std::string_view text, double& value) {
    text = trim(text);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
    return result.ec == std::errc() && result.ptr == text.data() + text.size() && !text.empty() &&
           std::isfinite(value);
  }

  int positiveInt(const Field& field) const {
    int value = 0;
    if (!parseInteger(field.value, value) || value <= 0) {
      failField(field, "expected a positive integer, found " + quoteForMessage(field.value));
    }
    return value;
  }

  std::vector<double> numberList(const Field& field) const {
    std::vector<double> values;
    for (const std::string_view item : listItems(field)) {
      double value = 0;
      if (!parseDouble(item, value)) {
        failField(field, "expected a finite number as item " + std::to_string(values.size() + 1) +
                             ", found " + quoteForMessage(item));
      }
      values.push_back(value);
    }
    return values;
  }

  template <typename List>
  void checkPerBand(const Field& field, const List& list, int bands) const {
    if (static_cast<long long>(list.size()) != bands) {
      failField(field, "expected " + std::to_string(bands) + " values (one per band), found " +
                           std::to_string(list.size()));
    }
  }

  EnviMapInfo mapInfo(const Field& field) const {
    const std::vector<std::string_view> items = listItems(field);
    const char* expected =
        "expected {projection, reference pixel x, reference pixel y, easting, northing, "
        "pixel size x, pixel size y[, zone, North|South][, datum][, units=...]}";
    if (items.size() < 7) {
      failField(field, std::string(expected) + ", found " + std::to_string(items.size()) + " items");
    }
    EnviMapInfo info;
    info.projection = std::string(items[0]);
    double* numbers[6] = {&info.reference_pixel_x, &info.reference_pixel_y, &info.easting,
                          &info.northing, &info.pixel_size_x, &info.pixel_size_y};
    const char* names[6] = {"reference pixel x", "reference pixel y", "easting",
                            "northing", "pixel size x", "pixel size y"};
    for (int k = 0; k < 6; ++k) {
      if (!parseDouble(items[k + 1], *numbers[k])) {
        failField(field, std::string("expected a finite number for ") + names[k] + " (item " +
                             std::to_string(k + 2) + "), found " + quoteForMessage(items[k + 1]));
      }
    }
    // Positional items after the numbers: [zone, hemisphere][, datum].
    std::vector<std::string_view> positional;
    for (std::size_t k = 7; k < items.size(); ++k) {
      const std::size_t equals = items[k].find('=');
      if (equals == std::string_view::npos) {
        positional.push_back(items[k]);
        continue;
      }
      const std::string name = normaliseKey(items[k].substr(0, equals));
      if (name != "units") {
        failField(field, "unsupported map info item " + quoteForMessage(items[k]) +
                             " (only units=... is understood; rotated rasters are not supported)");
      }
      info.units = std::string(trim(items[k].substr(equals + 1)));
    }
    std::size_t next = 0;
    const bool is_utm = lowercase(info.projection) == "utm";
    if (positional.size() >= 2 || is_utm) {
      if (positional.size() < 2) {
        failField(field, "UTM map info needs a zone and North|South after the pixel size");
      }
      if (!parseInteger(positional[0], info.zone) || (is_utm && (info.zone < 1 || info.zone > 60))) {
        failField(field, std::string("expected a ") + (is_utm ? "UTM zone 1..60" : "zone number") +
                             ", found " + quoteForMessage(positional[0]));
      }
      const std::string hemisphere = lowercase(positional[1]);
      if (hemisphere != "north" && hemisphere != "south") {
        failField(field, "expected North or South, found " + quoteForMessage(positional[1]));
      }
      info.north = hemisphere == "north";
      next = 2;
    }
    if (next < positional.size()) info.datum = std::string(positional[next++]);
    if (next < positional.size()) {
      failField(field, "unexpected map info item " + quoteForMessage(positional[next]));
    }
    return info;
  }

 private:
  std::filesystem::path path_;
  std::vector<Field> fields_;
  std::map<std::string, std::size_t> index_;
};

// Shortest text that reads back to the same double; fixed notation in the
// usual range of coordinates and wavelengths (500000, not 5e+05), because
// some GIS readers of `map info` do not take exponents.
std::string formatNumber(double value) {
  char buffer[64];
  const double magnitude = std::abs(value);
  const bool fixed = magnitude == 0 || (magnitude >= 1e-5 && magnitude < 1e16);
  const auto result = fixed ? std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::fixed)
                            : std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string formatList(const std::vector<double>& values) {
  std::string out = "{";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i % 8 == 0) ? "\n " : " ";
    out += formatNumber(values[i]);
    if (i + 1 < values.size()) out += ',';
  }
  return out + "}";
}

void checkWritable(const std::string& what, const std::string& text, bool multi_line_ok) {
  const bool bad_char = text.find_first_of(multi_line_ok ? "{}" : "{}\n\r") != std::string::npos;
  if (bad_char || text != trim(text)) {
    throw std::invalid_argument("ENVI header " + what + " '" + text +
                                "' cannot be written: braces, line breaks or surrounding blanks");
  }
}

}  // namespace

std::size_t bytesPerValue(EnviDataType type) {
  switch (type) {
    case EnviDataType::uint8: return 1;
    case EnviDataType::int16:
    case EnviDataType::uint16: return 2;
    case EnviDataType::int32:
    case EnviDataType::uint32:
    case EnviDataType::float32: return 4;
    case EnviDataType::float64: return 8;
  }
  throw std::invalid_argument("unknown ENVI data type " + std::to_string(static_cast<int>(type)));
}

const char* toString(EnviInterleave interleave) {
  switch (interleave) {
    case EnviInterleave::bsq: return "bsq";
    case EnviInterleave::bil: return "bil";
    case EnviInterleave::bip: return "bip";
  }
  return "?";
}

const char* toString(EnviDataType type) {
  switch (type) {
    case EnviDataType::uint8: return "uint8";
    case EnviDataType::int16: return "int16";
    case EnviDataType::int32: return "int32";
    case EnviDataType::float32: return "float32";
    case EnviDataType::float64: return "float64";
    case EnviDataType::uint16: return "uint16";
    case EnviDataType::uint32: return "uint32";
  }
  return "?";
}

std::uint64_t EnviHeader::dataBytes() const {
  return static_cast<std::uint64_t>(samples) * static_cast<std::uint64_t>(lines) *
         static_cast<std::uint64_t>(bands) * bytesPerValue(data_type);
}

namespace {

// The sizes of a header multiply into byte counts and offsets that a reader
// seeks to. In 64-bit arithmetic they can wrap around (a header offset of
// 2^64 - 806400 plus 806400 bytes of data is 0), so every product and sum is
// checked, against the largest offset a file can have (off_t: 2^63 - 1).
void checkDataSize(const HeaderParser& parser, const EnviHeader& header, const Field& bands) {
  constexpr std::uint64_t kLargestFile = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  std::uint64_t bytes = bytesPerValue(header.data_type);
  const std::uint64_t factors[] = {static_cast<std::uint64_t>(header.samples),
                                   static_cast<std::uint64_t>(header.lines),
                                   static_cast<std::uint64_t>(header.bands)};
  bool overflow = false;
  for (const std::uint64_t factor : factors) overflow = overflow || __builtin_mul_overflow(bytes, factor, &bytes);
  if (overflow || bytes > kLargestFile) {
    parser.failField(bands, "samples " + std::to_string(header.samples) + " x lines " +
                                std::to_string(header.lines) + " x bands " +
                                std::to_string(header.bands) + " x " +
                                std::to_string(bytesPerValue(header.data_type)) +
                                " bytes per value is larger than any file can be (2^63 bytes); "
                                "expected the sizes of a real raster");
  }
  std::uint64_t end = 0;
  if (__builtin_add_overflow(header.header_offset, bytes, &end) || end > kLargestFile) {
    parser.failField(*parser.find("header offset"),
                     std::to_string(header.header_offset) + " bytes before " +
                         std::to_string(bytes) +
                         " bytes of data is beyond the largest possible file (2^63 bytes); "
                         "expected the number of bytes that precede the data in the data file");
  }
}

}  // namespace

EnviHeader readEnviHeader(const std::filesystem::path& hdr_path) {
  return parseEnviHeader(readTextFile(hdr_path, kMaxEnviHeaderBytes), hdr_path);
}

EnviHeader parseEnviHeader(std::string_view raw, const std::filesystem::path& hdr_path) {
  HeaderParser parser(hdr_path);
  EnviHeader header;
  parser.tokenise(normaliseText(raw, hdr_path, TextEncoding::any_bytes), header.comments);

  const Field& samples = parser.require("samples");
  const Field& lines = parser.require("lines");
  const Field& bands = parser.require("bands");
  const Field& data_type = parser.require("data type");
  const Field& interleave = parser.require("interleave");
  header.samples = parser.positiveInt(samples);
  header.lines = parser.positiveInt(lines);
  header.bands = parser.positiveInt(bands);

  int code = 0;
  if (!HeaderParser::parseInteger(data_type.value, code) ||
      !(code == 1 || code == 2 || code == 3 || code == 4 || code == 5 || code == 12 || code == 13)) {
    parser.failField(data_type, std::string("expected ") + kDataTypeChoices + ", found " +
                                    quoteForMessage(data_type.value));
  }
  header.data_type = static_cast<EnviDataType>(code);

  const std::string interleave_text = lowercase(interleave.value);
  if (interleave_text == "bsq") {
    header.interleave = EnviInterleave::bsq;
  } else if (interleave_text == "bil") {
    header.interleave = EnviInterleave::bil;
  } else if (interleave_text == "bip") {
    header.interleave = EnviInterleave::bip;
  } else {
    parser.failField(interleave, "expected bsq, bil or bip, found " + quoteForMessage(interleave.value));
  }

  for (const Field& field : parser.fields()) {
    const std::string key = normaliseKey(field.key_text);
    if (key == "samples" || key == "lines" || key == "bands" || key == "data type" ||
        key == "interleave") {
      continue;
    } else if (key == "header offset") {
      if (!HeaderParser::parseInteger(field.value, header.header_offset)) {
        parser.failField(field, "expected a non-negative integer, found " + quoteForMessage(field.value));
      }
    } else if (key == "byte order") {
      if (field.value != "0" && field.value != "1") {
        parser.failField(field, "expected 0 (little endian) or 1 (big endian), found " +
                                    quoteForMessage(field.value));
      }
      header.byte_order = field.value == "1" ? 1 : 0;
    } else if (key == "file type") {
      header.file_type = std::string(HeaderParser::inner(field));
    } else if (key == "wavelength") {
      header.wavelength = parser.numberList(field);
      parser.checkPerBand(field, header.wavelength, header.bands);
    } else if (key == "fwhm") {
      header.fwhm = parser.numberList(field);
      parser.checkPerBand(field, header.fwhm, header.bands);
      for (std::size_t b = 0; b < header.fwhm.size(); ++b) {
        if (!(header.fwhm[b] > 0.0)) {
          parser.failField(field, "expected band widths > 0, found " +
                                      formatNumber(header.fwhm[b]) + " for band " +
                                      std::to_string(b + 1));
        }
      }
    } else if (key == "band names") {
      for (const std::string_view item : parser.listItems(field)) header.band_names.emplace_back(item);
      parser.checkPerBand(field, header.band_names, header.bands);
    } else if (key == "wavelength units") {
      header.wavelength_units = std::string(HeaderParser::inner(field));
    } else if (key == "map info") {
      header.map_info = parser.mapInfo(field);
    } else if (key == "description") {
      header.description = std::string(HeaderParser::inner(field));
    } else {
      header.other_fields.emplace_back(field.key_text, field.value);
    }
  }
  checkDataSize(parser, header, bands);
  return header;
}

std::string formatEnviHeader(const EnviHeader& header) {
  if (header.samples <= 0 || header.lines <= 0 || header.bands <= 0) {
    throw std::invalid_argument("ENVI header: samples, lines and bands must be positive");
  }
  if (header.byte_order != 0 && header.byte_order != 1) {
    throw std::invalid_argument("ENVI header: byte order must be 0 or 1");
  }
  bytesPerValue(header.data_type);  // throws for a code outside the enum
  const auto per_band = [&](std::size_t size, const char* what) {
    if (size != 0 && size != static_cast<std::size_t>(header.bands)) {
      throw std::invalid_argument(std::string("ENVI header: ") + what + " has " +
                                  std::to_string(size) + " entries for " +
                                  std::to_string(header.bands) + " bands");
    }
  };
  per_band(header.wavelength.size(), "wavelength");
  per_band(header.fwhm.size(), "fwhm");
  per_band(header.band_names.size(), "band names");
  checkWritable("description", header.description, true);
  checkWritable("file type", header.file_type, false);
  checkWritable("wavelength units", header.wavelength_units, false);
  for (const std::string& name : header.band_names) {
    checkWritable("band name", name, false);
    if (name.empty() || name.find(',') != std::string::npos) {
      throw std::invalid_argument("ENVI band name '" + name + "' must be non-empty, without commas");
    }
  }
  for (const std::string& comment : header.comments) checkWritable("comment", comment, false);

  std::ostringstream out;
  out << "ENVI\n";
  if (!header.description.empty()) out << "description = {\n" << header.description << "}\n";
  out << "samples = " << header.samples << "\n"
      << "lines = " << header.lines << "\n"
      << "bands = " << header.bands << "\n"
      << "header offset = " << header.header_offset << "\n"
      << "file type = " << header.file_type << "\n"
      << "data type = " << static_cast<int>(header.data_type) << "\n"
      << "interleave = " << toString(header.interleave) << "\n"
      << "byte order = " << header.byte_order << "\n";
  if (header.map_info) {
    const EnviMapInfo& info = *header.map_info;
    for (const std::string* text : {&info.projection, &info.datum, &info.units}) {
      if (text->find(',') != std::string::npos) {
        throw std::invalid_argument("ENVI map info item '" + *text + "' must not contain commas");
      }
      checkWritable("map info item", *text, false);
    }
    out << "map info = {" << info.projection << ", " << formatNumber(info.reference_pixel_x) << ", "
        << formatNumber(info.reference_pixel_y) << ", " << formatNumber(info.easting) << ", "
        << formatNumber(info.northing) << ", " << formatNumber(info.pixel_size_x) << ", "
        << formatNumber(info.pixel_size_y);
    if (lowercase(info.projection) == "utm" || info.zone != 0 || !info.north) {
      out << ", " << info.zone << ", " << (info.north ? "North" : "South");
    }
    if (!info.datum.empty()) out << ", " << info.datum;
    if (!info.units.empty()) out << ", units=" << info.units;
    out << "}\n";
  }
  if (!header.wavelength_units.empty()) out << "wavelength units = " << header.wavelength_units << "\n";
  if (!header.wavelength.empty()) out << "wavelength = " << formatList(header.wavelength) << "\n";
  if (!header.fwhm.empty()) out << "fwhm = " << formatList(header.fwhm) << "\n";
  if (!header.band_names.empty()) {
    out << "band names = {";
    for (std::size_t i = 0; i < header.band_names.size(); ++i) {
      out << ((i % 8 == 0) ? "\n " : " ") << header.band_names[i]
          << (i + 1 < header.band_names.size() ? "," : "");
    }
    out << "}\n";
  }
  for (const auto& [key, value] : header.other_fields) {
    checkWritable("key", key, false);
    if (key.find('=') != std::string::npos || key.empty()) {
      throw std::invalid_argument("ENVI header key '" + key + "' must be non-empty, without '='");
    }
    const bool braced = !value.empty() && value.front() == '{' && value.back() == '}' &&
                        value.find('}') == value.size() - 1;
    if (!braced && value.find_first_of("{}\n\r") != std::string::npos) {
      throw std::invalid_argument("ENVI header value of '" + key +
                                  "' must be one line, or a single '{ ... }' block");
    }
    if (value != trim(value)) {
      throw std::invalid_argument("ENVI header value of '" + key + "' has surrounding blanks");
    }
    out << key << " = " << value << "\n";
  }
  for (const std::string& comment : header.comments) out << "; " << comment << "\n";
  return out.str();
}

void writeEnviHeader(const std::filesystem::path& hdr_path, const EnviHeader& header) {
  const std::string text = formatEnviHeader(header);
  AtomicFile file(hdr_path);
  file.stream() << text;
  file.commit();
}

std::filesystem::path findEnviDataFile(const std::filesystem::path& hdr_path) {
  std::filesystem::path stem = hdr_path;
  stem.replace_extension();
  std::vector<std::filesystem::path> candidates;
  for (const char* extension : {".raw", ".img", ".dat", ".bsq", ".bil", ".bip"}) {
    std::filesystem::path candidate = stem;
    candidate += extension;
    candidates.push_back(candidate);
  }
  candidates.push_back(stem);
  std::string tried;
  for (const std::filesystem::path& candidate : candidates) {
    std::error_code ec;
    if (candidate != hdr_path && std::filesystem::is_regular_file(candidate, ec)) return candidate;
    tried += (tried.empty() ? "" : ", ") + candidate.filename().string();
  }
  throw InputError(hdr_path, "", "no data file found next to the header (tried " + tried + ")");
}

}  // namespace hsmap
