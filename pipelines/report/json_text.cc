#include "pipelines/report/json_text.h"

#include <cmath>
#include <cstdio>

#include "core/survey/number_text.h"

namespace hsmap {

std::string jsonString(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      case '<': out += "\\u003c"; break;
      case '>': out += "\\u003e"; break;
      case '&': out += "\\u0026"; break;
      default:
        if ((unsigned char)c < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", unsigned((unsigned char)c));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

void JsonText::separate() {
  if (needs_comma_) text_ += ',';
  needs_comma_ = true;
}

JsonText& JsonText::beginObject() {
  separate();
  text_ += '{';
  needs_comma_ = false;
  return *this;
}

JsonText& JsonText::endObject() {
  text_ += '}';
  needs_comma_ = true;
  return *this;
}

JsonText& JsonText::beginArray() {
  separate();
  text_ += '[';
  needs_comma_ = false;
  return *this;
}

JsonText& JsonText::endArray() {
  text_ += ']';
  needs_comma_ = true;
  return *this;
}

JsonText& JsonText::key(std::string_view name) {
  separate();
  text_ += jsonString(name);
  text_ += ':';
  needs_comma_ = false;  // the value follows without a comma
  return *this;
}

JsonText& JsonText::value(std::string_view text) {
  separate();
  text_ += jsonString(text);
  return *this;
}

JsonText& JsonText::value(double number) {
  separate();
  text_ += std::isfinite(number) ? formatDouble(number) : "null";
  return *this;
}

JsonText& JsonText::value(long long number) {
  separate();
  text_ += std::to_string(number);
  return *this;
}

JsonText& JsonText::value(bool flag) {
  separate();
  text_ += flag ? "true" : "false";
  return *this;
}

JsonText& JsonText::null() {
  separate();
  text_ += "null";
  return *this;
}

}  // namespace hsmap
