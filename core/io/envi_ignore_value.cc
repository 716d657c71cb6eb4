#include "core/io/envi_ignore_value.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

// `Data  Ignore Value` -> `data ignore value`.
std::string normalisedKey(const std::string& key) {
  std::string out;
  for (const char c : key) {
    if (std::isspace(static_cast<unsigned char>(c)) != 0) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace

std::optional<float> enviDataIgnoreValue(const EnviHeader& header, const std::filesystem::path& hdr_path) {
  for (const auto& [key, value] : header.other_fields) {
    if (normalisedKey(key) != "data ignore value") continue;
    std::string text = value;
    std::erase_if(text, [](char c) { return c == '{' || c == '}' || std::isspace(static_cast<unsigned char>(c)); });
    char* end = nullptr;
    const double number = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || std::isinf(number)) {
      throw InputError(hdr_path, InputError::atKey("data ignore value"),
                       "expected a finite number or NaN, found '" + value + "'");
    }
    if (std::isnan(number)) return std::nullopt;
    return static_cast<float>(number);
  }
  return std::nullopt;
}

void setDataIgnoreValueNaN(EnviHeader& header) {
  std::erase_if(header.other_fields,
                [](const auto& field) { return normalisedKey(field.first) == "data ignore value"; });
  header.other_fields.emplace_back("data ignore value", "NaN");
}

}  // namespace hsmap
