#pragma once
// EnviWriter: writes an ENVI cube line by line (lines in order), converting
// band-major float lines (in[b * samples + s], as EnviReader returns them)
// to the header's data type, byte order and interleave.
//
// Files: for `dir/cube.hdr` the data file is `dir/cube.raw`. While writing,
// the data goes to `cube.raw.partial`; finish() renames it to `cube.raw` and
// then writes `cube.hdr` (itself atomically), so a header never describes an
// incomplete data file. Destroying a writer without finish() removes the
// partial file: an interrupted run leaves nothing that looks whole.
//
// Layout: BIL and BIP lines are contiguous blocks written in turn; BSQ writes
// each band's row into that band's plane (pwrite), which is why BSQ needs the
// line count up front. For BIL/BIP, `lines = 0` in the header means "count
// the lines written" (finish() records the count). A header offset is
// written as zero bytes before the data.
//
// Write modes (EnviWriteMode):
// - buffered (default): each line is one pwrite through the page cache.
// - direct: for BIL/BIP with no header offset, lines are encoded into a 32 MB
//   staging buffer that goes to disk with O_DIRECT in whole 4 KB blocks
//   (the tail, at finish(), through the page cache). Two staging buffers
//   take turns: while one is written by a background thread, the next lines
//   are encoded into the other, so the device stays busy while the caller
//   computes (a write error surfaces on the next writeLine() or finish()).
//   Measured on the project's virtual machine (single buffer): 1.3 GB/s
//   against 0.2 GB/s buffered for a multi-GB file
//   (the page cache's writeback is the limit, and writing GBs through it also
//   evicts the input being read). For files much larger than the page cache
//   read back later by nobody soon, e.g. a hyperspectral ortho-image. Where
//   the file system refuses O_DIRECT (tmpfs), or for BSQ or a header offset,
//   it writes like buffered. The files are the same bytes in either mode.
//
// Conversion (envi_sample_codec.h): integers are rounded and clamped, NaN
// becomes 0. Header problems (non-positive samples/bands, list sizes not
// matching bands, hdr path not ending in .hdr) are std::invalid_argument;
// I/O failures are std::runtime_error naming the file; writing more lines
// than the header has, or finish() with lines missing, is std::logic_error.

#include <cstddef>
#include <filesystem>
#include <future>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/io/envi_header.h"

namespace hsmap {

enum class EnviWriteMode { buffered, direct };

class EnviWriter {
 public:
  EnviWriter(const std::filesystem::path& hdr_path, EnviHeader header,
             EnviWriteMode mode = EnviWriteMode::buffered);
  ~EnviWriter();
  EnviWriter(const EnviWriter&) = delete;
  EnviWriter& operator=(const EnviWriter&) = delete;

  const EnviHeader& header() const { return header_; }
  const std::filesystem::path& headerPath() const { return hdr_path_; }
  const std::filesystem::path& dataPath() const { return data_path_; }
  // Whether lines go out with O_DIRECT (direct asked for and possible).
  bool direct() const { return direct_; }
  int linesWritten() const { return lines_written_; }

  // One line, band-major: bands * samples floats.
  void writeLine(const float* band_major_line);
  // One line as a bands x samples matrix (row = band).
  void writeLine(const Eigen::MatrixXf& line);
  // One line that `fill(float* band_major_line)` writes, setting all
  // bands * samples floats. Where the file takes floats as they are (direct
  // mode, BIL, float32 in this machine's byte order) `fill` writes straight
  // into the staging buffer, which saves copying every line (for the
  // hyperspectral ortho-image, GBs the write thread copied); otherwise it
  // fills a scratch line that writeLine() encodes. The same bytes either way.
  template <class Fill>
  void writeLineWith(Fill&& fill) {
    if (float* staged = reserveStagedLine()) {
      fill(staged);
      commitStagedLine();
      return;
    }
    scratch_.resize(static_cast<std::size_t>(header_.samples) * static_cast<std::size_t>(header_.bands));
    fill(scratch_.data());
    writeLine(scratch_.data());
  }

  void finish();

 private:
  void writeAt(const std::byte* bytes, std::size_t size, std::size_t offset);
  // Direct mode: hands the staged whole blocks to a background write and
  // goes on staging into the other buffer (the partial last block moved over).
  void flushStagedBlocks();
  // Direct mode: waits for the background write; rethrows its error.
  void waitForPendingWrite();
  // Direct mode: writes whole blocks at `offset` (run on the background thread).
  void writeBlocks(const std::byte* bytes, std::size_t size, std::size_t offset);
  void abandon() noexcept;
  // Throws if no further line may be written.
  void checkLineAllowed() const;
  // Direct mode: room for one more line in the staging buffer (after a flush
  // if needed); commitStagedLine() counts the bytes put there.
  std::byte* stagedLineSlot();
  void commitStagedLine();
  // The slot as floats when the file takes them as they are, else nullptr.
  float* reserveStagedLine();

  std::filesystem::path hdr_path_;
  std::filesystem::path data_path_;
  std::filesystem::path partial_path_;
  EnviHeader header_;
  bool count_lines_ = false;  // header.lines == 0 on construction
  int fd_ = -1;
  bool swap_bytes_ = false;
  std::size_t value_bytes_ = 0;
  std::size_t line_bytes_ = 0;  // samples * bands * value_bytes_
  int lines_written_ = 0;
  bool finished_ = false;
  std::vector<std::byte> encoded_;
  std::vector<float> pixel_major_;
  std::vector<float> scratch_;  // writeLineWith() when the staging buffer cannot take floats
  // Direct mode: block-aligned staging buffer, bytes in it, file offset of its
  // start; the other buffer, being written by `pending_write_`.
  bool direct_ = false;
  bool floats_in_place_ = false;  // direct, BIL, float32, native byte order
  std::unique_ptr<std::byte, void (*)(void*)> staging_{nullptr, nullptr};
  std::unique_ptr<std::byte, void (*)(void*)> writing_{nullptr, nullptr};
  std::future<void> pending_write_;
  std::size_t staging_capacity_ = 0;
  std::size_t staged_ = 0;
  std::size_t staged_offset_ = 0;
};

}  // namespace hsmap
