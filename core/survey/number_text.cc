#include "core/survey/number_text.h"

#include <charconv>
#include <cmath>
#include <system_error>

#include "core/util/message_text.h"

namespace hsmap {

std::string_view trimBlanks(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

namespace {
// std::from_chars does not accept a leading '+', which spreadsheets write.
std::string_view dropPlus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') {
    return text.substr(1);
  }
  return text;
}
}  // namespace

std::optional<double> parseFiniteDouble(std::string_view text, std::string* message) {
  const std::string_view body = dropPlus(trimBlanks(text));
  double value = 0.0;
  const char* end = body.data() + body.size();
  const auto [ptr, ec] = std::from_chars(body.data(), end, value);
  if (body.empty() || ec != std::errc() || ptr != end) {
    if (message) *message = "expected a number, got " + quoteForMessage(text);
    return std::nullopt;
  }
  if (!std::isfinite(value)) {
    if (message) *message = "expected a finite number, got " + quoteForMessage(text);
    return std::nullopt;
  }
  return value;
}

std::optional<long long> parseInteger(std::string_view text, std::string* message) {
  const std::string_view body = dropPlus(trimBlanks(text));
  long long value = 0;
  const char* end = body.data() + body.size();
  const auto [ptr, ec] = std::from_chars(body.data(), end, value);
  if (body.empty() || ec != std::errc() || ptr != end) {
    if (message) *message = "expected an integer, got " + quoteForMessage(text);
    return std::nullopt;
  }
  return value;
}

std::string formatDouble(double value) {
  char buffer[64];
  // 64 characters always suffice for the shortest form of a double.
  const char* end = std::to_chars(buffer, buffer + sizeof(buffer), value).ptr;
  return std::string(buffer, static_cast<std::size_t>(end - buffer));
}

}  // namespace hsmap
