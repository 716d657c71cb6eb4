#include "core/survey/strict_yaml_map.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "core/util/text_file.h"

namespace hsmap {
namespace {

std::string joinKeys(const std::vector<std::string>& keys) {
  std::string text;
  for (std::size_t i = 0; i < keys.size(); ++i) text += (i > 0 ? ", " : "") + keys[i];
  return text;
}

std::string whereText(long long line, const std::string& dotted_key) {
  std::string text = InputError::atLine(line);
  if (!dotted_key.empty()) text += ", " + InputError::atKey(dotted_key);
  return text;
}

long long lineOfNode(const YAML::Node& node, long long fallback) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? fallback : mark.line + 1;
}

// Where a second YAML document starts in normalised `text`, or 0 when the
// text holds one document. A line that starts with "---" or "..." followed
// by a blank or its end is a document marker wherever it stands (YAML 1.2
// forbids such lines inside scalars), so markers are found on the text:
// yaml-cpp 0.7's LoadAll() cannot be used to count documents, since on some
// inputs (a lone ',') it produces empty documents without end.
long long secondDocumentLine(std::string_view text) {
  const auto isMarker = [](std::string_view line, std::string_view marker) {
    return line.substr(0, 3) == marker &&
           (line.size() == 3 || line[3] == ' ' || line[3] == '\t');
  };
  bool content = false;  // the first document has begun
  bool ended = false;    // its '...' end marker was seen
  long long line_number = 0;
  for (std::size_t start = 0; start <= text.size(); ++line_number) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    const std::size_t first = line.find_first_not_of(" \t");
    const bool blank = first == std::string_view::npos || line[first] == '#';
    if (isMarker(line, "---")) {
      if (content || ended) return line_number + 1;
      content = true;  // "--- value" opens the document on this line
    } else if (isMarker(line, "...")) {
      ended = ended || content;
    } else if (!blank && line[0] != '%') {  // '%' starts a directive, before '---'
      if (ended) return line_number + 1;
      content = true;
    }
    if (end == text.size()) break;
  }
  return 0;
}
}  // namespace

std::string describeYamlNode(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return quoteForMessage(node.Scalar());
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

YAML::Node parseYamlText(std::string_view raw, const std::filesystem::path& file) {
  const std::string text = normaliseText(raw, file, TextEncoding::utf8);
  if (const long long line = secondDocumentLine(text)) {
    // yaml-cpp's Load() would read the first document and drop the rest: a
    // file pasted twice, or notes after a '...' end marker, would be half
    // read without a word. Every hsmap YAML file is one document.
    throw InputError(file, InputError::atLine(line),
                     "a second YAML document starts here; expected the file to hold one "
                     "document (remove what follows the first '---' / '...' document marker)");
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {  // ParserException and the rest carry a mark
    throw InputError(file, InputError::atLine(e.mark.is_null() ? 1 : e.mark.line + 1),
                     "YAML syntax error: " + escapeForMessage(e.msg, 200));
  }
}

YAML::Node loadYamlFile(const std::filesystem::path& file) {
  return parseYamlText(readTextFile(file, kMaxYamlBytes), file);
}

StrictYamlMap::StrictYamlMap(std::filesystem::path file, const YAML::Node& node,
                             std::string dotted_key, long long line,
                             std::vector<std::string> allowed_keys)
    : file_(std::move(file)), dotted_key_(std::move(dotted_key)), line_(line) {
  if (!node.IsMap()) {
    throw InputError(
        file_, whereText(line_, dotted_key_),
        "expected a map with keys (" + joinKeys(allowed_keys) + "), got " + describeYamlNode(node));
  }
  line_ = lineOfNode(node, line_);
  for (auto it = node.begin(); it != node.end(); ++it) {
    const long long key_line = lineOfNode(it->first, line_);
    if (!it->first.IsScalar()) {
      throw InputError(file_, whereText(key_line, dotted_key_),
                       "expected a plain text key, got " + describeYamlNode(it->first));
    }
    const std::string key = it->first.Scalar();
    bool allowed = false;
    for (const auto& candidate : allowed_keys) allowed = allowed || candidate == key;
    if (!allowed) {
      throw InputError(file_, whereText(key_line, keyPath(escapeForMessage(key, 40))),
                       "unknown key; expected one of: " + joinKeys(allowed_keys));
    }
    if (const Entry* first = find(key)) {
      throw InputError(file_, whereText(key_line, keyPath(key)),
                       "duplicated key (first given at line " + std::to_string(first->line) + ")");
    }
    entries_.push_back({key, key_line, it->second});
  }
}

bool StrictYamlMap::has(const std::string& key) const { return find(key) != nullptr; }

std::string StrictYamlMap::keyPath(const std::string& key) const {
  return dotted_key_.empty() ? key : dotted_key_ + "." + key;
}

long long StrictYamlMap::lineOf(const std::string& key) const {
  const Entry* entry = find(key);
  return entry ? entry->line : line_;
}

std::string StrictYamlMap::where(const std::string& key) const {
  return whereText(lineOf(key), keyPath(key));
}

void StrictYamlMap::fail(const std::string& key, const std::string& detail) const {
  throw InputError(file_, where(key), detail);
}

const StrictYamlMap::Entry* StrictYamlMap::find(const std::string& key) const {
  for (const auto& entry : entries_) {
    if (entry.key == key) return &entry;
  }
  return nullptr;
}

const StrictYamlMap::Entry& StrictYamlMap::require(const std::string& key) const {
  const Entry* entry = find(key);
  if (!entry) fail(key, "missing required key");
  return *entry;
}

double StrictYamlMap::parseNumber(const YAML::Node& value, const std::string& key, long long line,
                                  const std::string& shown_key) const {
  std::string message;
  if (value.IsScalar()) {
    if (const auto number = parseFiniteDouble(value.Scalar(), &message)) return *number;
  } else {
    message = "expected a number, got " + describeYamlNode(value);
  }
  throw InputError(file_, whereText(line, shown_key), message);
}

double StrictYamlMap::number(const std::string& key) const {
  const Entry& entry = require(key);
  return parseNumber(entry.value, key, entry.line, keyPath(key));
}

double StrictYamlMap::positiveNumber(const std::string& key) const {
  const double value = number(key);
  if (!(value > 0.0)) fail(key, "expected a number > 0, got " + formatDouble(value));
  return value;
}

int StrictYamlMap::positiveInteger(const std::string& key) const {
  const Entry& entry = require(key);
  std::string message;
  std::optional<long long> value;
  if (entry.value.IsScalar()) {
    value = parseInteger(entry.value.Scalar(), &message);
  } else {
    message = "expected an integer, got " + describeYamlNode(entry.value);
  }
  if (!value) fail(key, message);
  if (*value <= 0 || *value > std::numeric_limits<int>::max()) {
    fail(key, "expected an integer > 0, got " + std::to_string(*value));
  }
  return static_cast<int>(*value);
}

std::string StrictYamlMap::text(const std::string& key) const {
  const Entry& entry = require(key);
  if (!entry.value.IsScalar() || entry.value.Scalar().empty()) {
    fail(key, "expected a non-empty text value, got " + describeYamlNode(entry.value));
  }
  const std::string& value = entry.value.Scalar();
  // The file's bytes were checked by parseYamlText(), but a double-quoted
  // scalar can still spell control characters as escapes ("\0", "\x01"):
  // a NUL would silently cut a file name handed to the operating system.
  for (const char c : value) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) {
      fail(key, "expected printable text, got " + quoteForMessage(value) +
                    " (it holds a control character)");
    }
  }
  if (value.size() > kMaxTextValueBytes) {
    fail(key, "expected a text of at most " + std::to_string(kMaxTextValueBytes) +
                  " bytes, got " + quoteForMessage(value));
  }
  return value;
}

std::vector<double> StrictYamlMap::numbers(const std::string& key, std::size_t count) const {
  const Entry& entry = require(key);
  const std::string expected = "expected a list of " + std::to_string(count) + " numbers";
  if (!entry.value.IsSequence()) fail(key, expected + ", got " + describeYamlNode(entry.value));
  if (entry.value.size() != count) {
    fail(key, expected + ", got a list of " + std::to_string(entry.value.size()));
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < count; ++i) {
    const YAML::Node element = entry.value[i];
    values.push_back(parseNumber(element, key, lineOfNode(element, entry.line),
                                 keyPath(key) + "[" + std::to_string(i) + "]"));
  }
  return values;
}

StrictYamlMap StrictYamlMap::map(const std::string& key,
                                 std::vector<std::string> allowed_keys) const {
  const Entry& entry = require(key);
  return StrictYamlMap(file_, entry.value, keyPath(key), entry.line, std::move(allowed_keys));
}

std::vector<StrictYamlMap> StrictYamlMap::maps(const std::string& key,
                                               const std::vector<std::string>& allowed_keys) const {
  const Entry& entry = require(key);
  if (!entry.value.IsSequence()) {
    fail(key, "expected a list of maps with keys (" + joinKeys(allowed_keys) + "), got " +
                  describeYamlNode(entry.value));
  }
  std::vector<StrictYamlMap> elements;
  elements.reserve(entry.value.size());
  for (std::size_t i = 0; i < entry.value.size(); ++i) {
    const YAML::Node element = entry.value[i];
    elements.emplace_back(file_, element, keyPath(key) + "[" + std::to_string(i) + "]",
                          lineOfNode(element, entry.line), allowed_keys);
  }
  return elements;
}

double StrictYamlMap::numberInRange(const std::string& key, double low, double high) const {
  const double value = number(key);
  if (value < low || value > high) {
    fail(key, "expected a number in [" + formatDouble(low) + ", " + formatDouble(high) +
                  "], got " + formatDouble(value));
  }
  return value;
}

double StrictYamlMap::positiveNumberUpTo(const std::string& key, double high) const {
  const double value = positiveNumber(key);
  if (value > high) {
    fail(key, "expected a number in (0, " + formatDouble(high) + "], got " + formatDouble(value));
  }
  return value;
}

int StrictYamlMap::positiveIntegerUpTo(const std::string& key, int high) const {
  const int value = positiveInteger(key);
  if (value > high) {
    fail(key, "expected an integer in [1, " + std::to_string(high) + "], got " +
                  std::to_string(value));
  }
  return value;
}

double StrictYamlMap::numberInRange(const std::string& key, double low, double high,
                                    double default_value) const {
  return has(key) ? numberInRange(key, low, high) : default_value;
}

double StrictYamlMap::positiveNumberUpTo(const std::string& key, double high,
                                         double default_value) const {
  return has(key) ? positiveNumberUpTo(key, high) : default_value;
}

double StrictYamlMap::number(const std::string& key, double default_value) const {
  return has(key) ? number(key) : default_value;
}

double StrictYamlMap::positiveNumber(const std::string& key, double default_value) const {
  return has(key) ? positiveNumber(key) : default_value;
}

std::vector<double> StrictYamlMap::numbers(const std::string& key, std::size_t count,
                                           std::vector<double> default_value) const {
  return has(key) ? numbers(key, count) : default_value;
}

}  // namespace hsmap
