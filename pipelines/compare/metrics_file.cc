#include "pipelines/compare/metrics_file.h"

#include <cctype>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"
#include "core/util/text_file.h"

namespace hsmap {

namespace {

// A recursive-descent reader of one JSON value at a time; only the top
// object's scalar members are kept.
class JsonReader {
 public:
  JsonReader(std::string_view text, const std::filesystem::path& file) : text_(text), file_(file) {}

  MetricFigures readTopObject() {
    MetricFigures figures;
    expect('{');
    skipBlanks();
    if (peek() == '}') {
      ++at_;
    } else {
      while (true) {
        skipBlanks();
        const std::string key = readString();
        expect(':');
        skipBlanks();
        if (peek() == 'n' || peek() == '-' || std::isdigit(static_cast<unsigned char>(peek()))) {
          figures.emplace_back(key, readNumberOrNull());
        } else {
          skipValue();
        }
        skipBlanks();
        if (peek() == ',') {
          ++at_;
          continue;
        }
        expect('}');
        break;
      }
    }
    skipBlanks();
    if (at_ != text_.size()) fail("expected the end of the file after the top object");
    return figures;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(file_, "byte " + std::to_string(at_), what);
  }
  char peek() const {
    if (at_ >= text_.size()) fail("expected more: the file ends here (truncated?)");
    return text_[at_];
  }
  void skipBlanks() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  void expect(char c) {
    skipBlanks();
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++at_;
  }
  std::string readString() {
    if (peek() != '"') fail("expected a string");
    std::string value;
    for (++at_; at_ < text_.size() && text_[at_] != '"'; ++at_) {
      if (text_[at_] == '\\') ++at_;  // the escaped character (keys and names hold none that matter)
      if (at_ < text_.size()) value += text_[at_];
    }
    if (at_ >= text_.size()) fail("a string that does not end");
    ++at_;
    return value;
  }
  std::optional<double> readNumberOrNull() {
    if (text_.substr(at_, 4) == "null") {
      at_ += 4;
      return std::nullopt;
    }
    const std::size_t start = at_;
    while (at_ < text_.size() && (std::isdigit(static_cast<unsigned char>(text_[at_])) ||
                                  std::string_view("+-.eE").find(text_[at_]) != std::string_view::npos)) {
      ++at_;
    }
    std::string message;
    const auto value = parseFiniteDouble(text_.substr(start, at_ - start), &message);
    if (!value) {
      at_ = start;
      fail("expected a number or null: " + message);
    }
    return value;
  }
  void skipValue() {
    skipBlanks();
    const char c = peek();
    if (c == '"') {
      readString();
    } else if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++at_;
      skipBlanks();
      if (peek() == close) {
        ++at_;
        return;
      }
      while (true) {
        if (c == '{') {
          skipBlanks();
          readString();
          expect(':');
        }
        skipValue();
        skipBlanks();
        if (peek() == ',') {
          ++at_;
          continue;
        }
        expect(close);
        return;
      }
    } else if (text_.substr(at_, 4) == "true") {
      at_ += 4;
    } else if (text_.substr(at_, 5) == "false") {
      at_ += 5;
    } else {
      readNumberOrNull();
    }
  }

  std::string_view text_;
  const std::filesystem::path& file_;
  std::size_t at_ = 0;
};

}  // namespace

MetricFigures parseMetricsJson(std::string_view text, const std::filesystem::path& file) {
  return JsonReader(text, file).readTopObject();
}

MetricFigures readMetricsFile(const std::filesystem::path& file) {
  return parseMetricsJson(readTextFile(file, kMaxYamlBytes), file);
}

}  // namespace hsmap
