#pragma once
// EnviReader: streams the scan lines of an ENVI cube (the UHI data, lines in
// time order) one line at a time, whatever the file's interleave, data type
// and byte order. The cube is never loaded whole: a 2 GB cube streams with a
// resident set of a few tens of MB.
//
// Layout (ENVI): with S samples, L lines, B bands and K bytes per value, the
// value (line l, band b, sample s) is at byte header_offset + K * i, where
//   bsq: i = (b * L + l) * S + s      one plane per band
//   bil: i = (l * B + b) * S + s      each line is B rows of S samples
//   bip: i = (l * S + s) * B + b      each line is S pixels of B bands
// readLine returns the line band-major (out[b * S + s]), i.e. as a B x S
// matrix: BIL is converted straight through, BIP is converted and transposed
// together (decodeSamplesTransposed), BSQ gathers one row from each band plane.
// readLinePixelMajor returns it pixel-major (out[s * B + b], each sample's
// spectrum contiguous): BIP straight through, BIL converted and transposed
// together, BSQ gathered and then transposed.
//
// Two ways to reach the bytes (EnviReadMode):
// - buffered (default): pread into a reused window of consecutive lines,
//   about 1 MB for BIL/BIP (converted while still in the CPU caches) and
//   4 MB for BSQ (one pread per band plane per window). Reading line l + 1
//   after line l loads the next window when needed; any other access loads
//   just that line. Memory stays at the window's size.
// - mapped: a read-only memory map (MappedFile, MADV_SEQUENTIAL). When lines
//   are read in increasing order the reader drops the pages behind the
//   cursor every ~16 MB (for BSQ, whose cursor is in every band plane, all
//   mapped pages), because the pages of a file mapping count in the resident
//   set for as long as they stay mapped.
// Both give identical results. Buffered is the default because it is several
// times faster where touching fresh mapped pages is expensive (measured on
// the project's virtual machine: docs/BENCHMARKS.md, "ENVI streaming read").
//
// Validation on construction (InputError): the header (readEnviHeader); a
// data file exists (findEnviDataFile); its size is at least
// header_offset + dataBytes(), else
//   "<data>: truncated: expected at least N bytes (...), found M".
// readLine is thread-safe (buffered: calls are serialised by a mutex, so use
// one reader per thread to read in parallel).

#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/Core>

#include "core/io/envi_header.h"
#include "core/io/mapped_file.h"
#include "core/io/positioned_file.h"

namespace hsmap {

enum class EnviReadMode { buffered, mapped };
enum class EnviLineLayout { band_major, pixel_major };

class EnviReader {
 public:
  explicit EnviReader(const std::filesystem::path& hdr_path, EnviReadMode mode = EnviReadMode::buffered);

  const EnviHeader& header() const { return header_; }
  const std::filesystem::path& headerPath() const { return hdr_path_; }
  const std::filesystem::path& dataPath() const { return data_path_; }
  EnviReadMode mode() const { return mode_; }
  int samples() const { return header_.samples; }
  int lines() const { return header_.lines; }
  int bands() const { return header_.bands; }

  // Scan line `line` (0-based) as float32, band-major: out[b * samples + s];
  // `out` holds bands * samples floats. std::out_of_range for a bad line.
  void readLine(int line, float* out) const;
  // Same, resized to bands x samples (row = band).
  void readLine(int line, Eigen::MatrixXf& out) const;
  // Scan line `line` pixel-major: out[s * bands + b], the layout in which
  // products average spectra. One pass over the line for BIL and BIP, where
  // readLine followed by a transpose would take two.
  void readLinePixelMajor(int line, float* out) const;

 private:
  void read(int line, EnviLineLayout layout, float* out) const;
  // Converts one line whose first value is at `start`; for BSQ, band b's row
  // starts at start + b * band_stride bytes.
  void decodeLine(const std::byte* start, std::size_t band_stride, EnviLineLayout layout, float* out) const;
  void readBuffered(int line, EnviLineLayout layout, float* out) const;
  void readMapped(int line, EnviLineLayout layout, float* out) const;
  void releaseBehind(int line) const;

  std::filesystem::path hdr_path_;
  EnviHeader header_;
  std::filesystem::path data_path_;
  EnviReadMode mode_;
  bool swap_bytes_ = false;
  std::size_t value_bytes_ = 0;
  std::size_t line_values_ = 0;  // bands * samples
  std::size_t line_bytes_ = 0;
  std::size_t row_bytes_ = 0;    // samples * value bytes: one band of one line
  int window_lines_ = 1;         // lines per window (buffered) or per release batch (mapped)

  // buffered
  std::unique_ptr<PositionedFile> file_;
  mutable std::mutex window_mutex_;
  mutable std::vector<std::byte> window_;
  mutable int window_first_ = 0;
  mutable int window_count_ = 0;
  mutable int last_line_ = -1;

  // mapped
  std::unique_ptr<MappedFile> map_;
  mutable std::atomic<int> released_lines_{0};  // lines [0, released) are unmapped
};

}  // namespace hsmap
