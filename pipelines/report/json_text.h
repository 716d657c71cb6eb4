#pragma once
// JsonText: appends JSON to a string, for the data the report page reads.
// The text may sit inside an HTML <script> element, so '<', '>' and '&' in
// strings are written as \u003c, \u003e and \u0026: no "</script>" can end the
// element early, whatever a file name or warning holds. Non-finite numbers
// are written null (JSON has no NaN).

#include <string>
#include <string_view>

namespace hsmap {

class JsonText {
 public:
  JsonText& beginObject();
  JsonText& endObject();
  JsonText& beginArray();
  JsonText& endArray();
  JsonText& key(std::string_view name);
  JsonText& value(std::string_view text);
  JsonText& value(const char* text) { return value(std::string_view(text)); }
  JsonText& value(const std::string& text) { return value(std::string_view(text)); }
  JsonText& value(double number);
  JsonText& value(int number) { return value(double(number)); }
  JsonText& value(long long number);
  JsonText& value(bool flag);
  JsonText& null();

  const std::string& text() const { return text_; }

 private:
  void separate();

  std::string text_;
  bool needs_comma_ = false;
};

// `text` as a JSON string literal, quotes included (escaped as above).
std::string jsonString(std::string_view text);

}  // namespace hsmap
