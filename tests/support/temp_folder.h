#pragma once
// Test helpers shared by every test program: TempFolder, a unique folder
// under the system temp directory removed with everything in it when the
// object goes out of scope (named after the label, or the running test), and
// small file helpers.

#include <unistd.h>

#include <atomic>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace hsmap::testing {

class TempFolder {
 public:
  // `label` names the folder; empty: the name of the running test.
  explicit TempFolder(const std::string& label = "") {
    static std::atomic<int> counter{0};
    std::string name = label;
    if (name.empty()) {
      const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
      name = info != nullptr ? info->name() : "test";
    }
    for (char& c : name) {
      if (c == '/') c = '_';
    }
    path_ = std::filesystem::temp_directory_path() /
            ("hsmap-test-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  // Writes `content` verbatim (binary) to `name` and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& content) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream out(file, std::ios::binary);
    out << content;
    return file;
  }

  // The bytes of `file`; empty when it cannot be read.
  static std::string read(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

 private:
  std::filesystem::path path_;
};

inline void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("test: cannot write " + file.string());
}

inline std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("test: cannot read " + file.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Number of '\n'-terminated lines of a text file.
inline long long countLines(const std::filesystem::path& file) {
  const std::string text = readText(file);
  return static_cast<long long>(std::count(text.begin(), text.end(), '\n'));
}

// Replaces the one occurrence of `from` in `file` by `to`; throws when `from`
// is not found exactly once, so a test cannot silently corrupt nothing.
inline void replaceInFile(const std::filesystem::path& file, const std::string& from,
                          const std::string& to) {
  std::string text = readText(file);
  const auto at = text.find(from);
  if (at == std::string::npos || text.find(from, at + 1) != std::string::npos) {
    throw std::runtime_error("test: '" + from + "' not found exactly once in " + file.string());
  }
  text.replace(at, from.size(), to);
  writeText(file, text);
}

// Copies the folder `from` (recursively) to the new path `to`.
inline void copyFolder(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::filesystem::copy(from, to, std::filesystem::copy_options::recursive);
}

}  // namespace hsmap::testing
