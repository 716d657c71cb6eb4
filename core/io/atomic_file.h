#pragma once
// AtomicFile: write a file under a temporary name and move it into place only
// when it is complete, so that a failed or interrupted run never leaves a
// half-written product under its final name (DESIGN.md, reliability shape).
//
// Contract
// - The content goes to `<path>.partial` in the same directory (so the final
//   rename(2) stays on one file system and is atomic).
// - Mode::stream opens that file as a binary std::ofstream (stream());
//   Mode::byPath opens nothing: a library that writes by file name (OpenCV,
//   GDAL, ...) writes partialPath() itself.
// - commit() flushes and closes the stream, checks that every write
//   succeeded (or, by path, that the library created the file) and renames
//   the partial file onto `path`, replacing an older file of that name.
// - Destroying an AtomicFile that was not committed removes the partial
//   file; the final name is never touched.
// - Output failures (cannot create, write or rename) throw std::runtime_error
//   naming the file and the system's reason.

#include <filesystem>
#include <fstream>
#include <string>

namespace hsmap {

class AtomicFile {
 public:
  enum class Mode { stream, byPath };

  explicit AtomicFile(std::filesystem::path path, Mode mode = Mode::stream);
  ~AtomicFile();
  AtomicFile(AtomicFile&& other) noexcept;
  AtomicFile& operator=(AtomicFile&& other) noexcept;
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // The final name and the temporary one (`<path>.partial`).
  const std::filesystem::path& path() const { return path_; }
  const std::filesystem::path& partialPath() const { return partial_path_; }
  // The binary output stream (Mode::stream only; std::logic_error otherwise).
  std::ofstream& stream();

  void commit();
  bool committed() const { return committed_; }

  // `<path>.partial`: the temporary name every hsmap writer uses.
  static std::filesystem::path partialPathFor(const std::filesystem::path& path);

 private:
  void abandon() noexcept;

  std::filesystem::path path_;
  std::filesystem::path partial_path_;
  Mode mode_ = Mode::stream;
  std::ofstream stream_;
  bool committed_ = false;
};

// `text` written to `path` through an AtomicFile (small text products:
// tables, summaries, records).
void writeTextAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace hsmap
