#include "core/survey/results_yaml.h"

#include <optional>

#include "core/survey/number_text.h"
#include "core/survey/run_variants.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"

namespace hsmap {

std::string readRunVariant(const StrictYamlMap& map, const std::string& key) {
  const std::string variant = map.text(key);
  if (!isRunVariant(variant)) {
    map.fail(key, "unknown variant " + quoteForMessage(variant) + "; expected one of: " +
                      runVariantList());
  }
  return variant;
}

std::optional<Eigen::Vector3d> readNullableSigmas(const StrictYamlMap& map,
                                                  const YAML::Node& value,
                                                  const std::string& key) {
  if (!map.has(key)) map.fail(key, "missing required key");
  if (value.IsNull()) return std::nullopt;
  const std::string expected = "expected a list of 3 numbers >= 0 or null (not estimated)";
  if (!value.IsSequence()) map.fail(key, expected + ", got " + describeYamlNode(value));
  const std::vector<double> numbers = map.numbers(key, 3);
  for (std::size_t i = 0; i < 3; ++i) {
    if (numbers[i] < 0.0) {
      throw InputError(map.file(), listElementWhere(map, value[i], key, i),
                       "expected a number >= 0, got " + formatDouble(numbers[i]));
    }
  }
  return Eigen::Vector3d(numbers[0], numbers[1], numbers[2]);
}

std::optional<double> readNullableSigma(const StrictYamlMap& map, const YAML::Node& value,
                                        const std::string& key) {
  if (!map.has(key)) map.fail(key, "missing required key");
  if (value.IsNull()) return std::nullopt;
  if (!value.IsScalar()) {
    map.fail(key, "expected a number >= 0 or null (not estimated), got " +
                      describeYamlNode(value));
  }
  return readNonNegativeNumber(map, key);
}

double readNonNegativeNumber(const StrictYamlMap& map, const std::string& key) {
  const double number = map.number(key);
  if (number < 0.0) map.fail(key, "expected a number >= 0, got " + formatDouble(number));
  return number;
}

std::string listElementWhere(const StrictYamlMap& map, const YAML::Node& element,
                             const std::string& key, std::size_t index) {
  const YAML::Mark mark = element.Mark();
  const long long line = mark.is_null() ? map.lineOf(key) : mark.line + 1;
  return InputError::atLine(line) + ", " +
         InputError::atKey(map.keyPath(key) + "[" + std::to_string(index) + "]");
}

void requirePrintableText(const std::filesystem::path& file, const std::string& where,
                          const std::string& text) {
  // As StrictYamlMap::text(): a quoted scalar can spell control characters
  // as escapes, which would break the one-line rule of messages and reports.
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) {
      throw InputError(file, where,
                       "expected printable text, got " + quoteForMessage(text) +
                           " (it holds a control character)");
    }
  }
  if (text.size() > StrictYamlMap::kMaxTextValueBytes) {
    throw InputError(file, where,
                     "expected a text of at most " +
                         std::to_string(StrictYamlMap::kMaxTextValueBytes) + " bytes, got " +
                         quoteForMessage(text));
  }
}

std::vector<std::string> readTextList(const StrictYamlMap& map, const YAML::Node& value,
                                      const std::string& key) {
  if (!map.has(key)) map.fail(key, "missing required key");
  if (!value.IsSequence()) {
    map.fail(key, "expected a list of texts (possibly empty: []), got " + describeYamlNode(value));
  }
  std::vector<std::string> texts;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const YAML::Node element = value[i];
    const std::string where = listElementWhere(map, element, key, i);
    if (!element.IsScalar() || element.Scalar().empty()) {
      throw InputError(map.file(), where,
                       "expected a non-empty text, got " + describeYamlNode(element));
    }
    requirePrintableText(map.file(), where, element.Scalar());
    texts.push_back(element.Scalar());
  }
  return texts;
}

}  // namespace hsmap
