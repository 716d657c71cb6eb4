#include "core/survey/strict_yaml_map.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"
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

}  // namespace

std::string describeYamlNode(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "nothing";
  }
}

YAML::Node loadYamlFile(const std::filesystem::path& file) {
  const std::string text = readTextFile(file);
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {  // ParserException and the rest carry a mark
    throw InputError(file, InputError::atLine(e.mark.is_null() ? 1 : e.mark.line + 1),
                     "YAML syntax error: " + e.msg);
  }
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
      throw InputError(file_, whereText(key_line, keyPath(key)),
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
  return entry.value.Scalar();
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
