#pragma once
// InputError: the one exception hsmap throws for bad input data.
//
// Users must be told precisely what is wrong with their files, so every
// error names the file, where in it (a line number, a YAML key, a byte
// offset, or nothing when the whole file is at fault) and what was expected.
// what() renders as
//     <file>:<where>: <detail>        e.g. "nav/ins.csv:line 12: column 'lat': expected a number, got 'abc'"
//     <file>: <detail>                when `where` is empty.

#include <filesystem>
#include <stdexcept>
#include <string>

namespace hsmap {

class InputError : public std::runtime_error {
 public:
  InputError(std::filesystem::path file, std::string where, std::string detail);

  const std::filesystem::path& file() const { return file_; }
  const std::string& where() const { return where_; }
  const std::string& detail() const { return detail_; }

  // "line 12", the conventional `where` for line-oriented text files (1-based).
  static std::string atLine(long long line_number);
  // "key rgb.camera.fx", the conventional `where` for YAML keys.
  static std::string atKey(const std::string& dotted_key);

 private:
  std::filesystem::path file_;
  std::string where_;
  std::string detail_;
};

}  // namespace hsmap
