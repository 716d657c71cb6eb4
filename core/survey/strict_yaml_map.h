#pragma once
// StrictYamlMap: reads one YAML mapping of an hsmap file (survey.yaml,
// truth/calibration.yaml, ...) strictly, so that every mistake in a
// hand-written file is reported instead of silently ignored:
//   - every key must be one of the keys the reader knows (a typo such as
//     `sigma_rotaton_deg` would otherwise fall back to a default unnoticed);
//   - a key may appear only once (yaml-cpp keeps both copies of a duplicate);
//   - a required key must be present;
//   - a value must have the expected type (number, integer, text, list, map)
//     and range; numbers are parsed by number_text.h, so "nan", "inf" and
//     "12abc" are rejected.
// Every error is an InputError whose `where` names the line and the dotted
// key, e.g. "survey.yaml:line 7, key rgb.camera.fx: expected a number > 0, got -800".
// The line is the key's own line (yaml-cpp's 0-based Mark + 1); for a
// missing key it is the line where the enclosing map starts.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace hsmap {

class StrictYamlMap {
 public:
  // `node` is the value found at `dotted_key` ("" for the document root) and
  // `line` the 1-based line to report when `node` itself is at fault. Throws
  // InputError when `node` is not a map or holds an unknown or duplicated key.
  StrictYamlMap(std::filesystem::path file, const YAML::Node& node, std::string dotted_key,
                long long line, std::vector<std::string> allowed_keys);

  const std::filesystem::path& file() const { return file_; }
  const std::string& dottedKey() const { return dotted_key_; }
  bool has(const std::string& key) const;
  // "rgb.camera" + "fx" -> "rgb.camera.fx".
  std::string keyPath(const std::string& key) const;
  // 1-based line of `key`, or of the map itself when `key` is absent.
  long long lineOf(const std::string& key) const;
  // "line 7, key rgb.camera.fx".
  std::string where(const std::string& key) const;
  // Throws InputError(file, where(key), detail).
  [[noreturn]] void fail(const std::string& key, const std::string& detail) const;

  // Required values (missing -> "missing required key").
  double number(const std::string& key) const;
  double positiveNumber(const std::string& key) const;  // > 0
  int positiveInteger(const std::string& key) const;    // integer > 0
  // A non-empty scalar of printable characters (no control characters, even
  // as YAML escapes), at most kMaxTextValueBytes long.
  std::string text(const std::string& key) const;
  static constexpr std::size_t kMaxTextValueBytes = 4096;
  // A list of exactly `count` numbers.
  std::vector<double> numbers(const std::string& key, std::size_t count) const;
  StrictYamlMap map(const std::string& key, std::vector<std::string> allowed_keys) const;
  // A list of maps (e.g. `lights.lamps`), each read strictly with
  // `allowed_keys`. Element i is named "<key>[i]" in errors (dotted keys
  // below it: "lights.lamps[1].axis") and reported at its own line. The list
  // may be empty: whether that is allowed is the caller's to say.
  std::vector<StrictYamlMap> maps(const std::string& key,
                                  const std::vector<std::string>& allowed_keys) const;

  // A number in [low, high] ("expected a number in [low, high], got v"), and
  // a number in (0, high] ("expected a number > 0" / "... in (0, high]"):
  // finite is not enough for physical quantities (a focal length of 1e308).
  double numberInRange(const std::string& key, double low, double high) const;
  double positiveNumberUpTo(const std::string& key, double high) const;
  // An integer in [1, high].
  int positiveIntegerUpTo(const std::string& key, int high) const;

  // Optional values: `default_value` when the key is absent.
  double numberInRange(const std::string& key, double low, double high,
                       double default_value) const;
  double positiveNumberUpTo(const std::string& key, double high, double default_value) const;
  double number(const std::string& key, double default_value) const;
  double positiveNumber(const std::string& key, double default_value) const;
  std::vector<double> numbers(const std::string& key, std::size_t count,
                              std::vector<double> default_value) const;

 private:
  struct Entry {
    std::string key;
    long long line;
    YAML::Node value;
  };
  const Entry* find(const std::string& key) const;
  const Entry& require(const std::string& key) const;
  double parseNumber(const YAML::Node& value, const std::string& key, long long line,
                     const std::string& shown_key) const;

  std::filesystem::path file_;
  std::string dotted_key_;
  long long line_;
  std::vector<Entry> entries_;
};

// A short description of what a YAML node holds, for "expected X, got Y"
// messages: "'abc'" for a scalar, "a list", "a map", "nothing".
std::string describeYamlNode(const YAML::Node& node);

// Parses the one YAML document of `raw`, the content of `file` (named in
// errors): the text checks of text_file.h (UTF-8, no control characters; CR
// and CRLF line ends accepted), then yaml-cpp. A syntax error is an
// InputError at its line, and so is a second document (content after a
// '...' or '---' marker): every hsmap YAML file holds exactly one. Empty
// text yields a Null node.
YAML::Node parseYamlText(std::string_view raw, const std::filesystem::path& file);

// parseYamlText() of `file`, read with the limit kMaxYamlBytes (text_file.h).
YAML::Node loadYamlFile(const std::filesystem::path& file);

}  // namespace hsmap
