#include "core/io/envi_reader.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/io/envi_sample_codec.h"
#include "core/io/float_transpose.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

// Mapped: pages are released in batches of this many bytes, so that
// madvise calls are rare and the resident set stays low.
constexpr std::size_t kReleaseBatchBytes = 16u << 20;
// Buffered BIL/BIP: a window of about 1 MB (at least one line) is read and
// converted while it is still in the CPU caches.
constexpr std::size_t kLineWindowBytes = 1u << 20;
// Buffered BSQ: one pread per band plane per window, so the window is larger
// to keep the number of syscalls down (211 bands x 1920 uint16 samples: one
// pread per band every 5 lines). 4 and 16 MB measured equally fast.
constexpr std::size_t kPlaneWindowBytes = 4u << 20;

}  // namespace

EnviReader::EnviReader(const std::filesystem::path& hdr_path, EnviReadMode mode)
    : hdr_path_(hdr_path),
      header_(readEnviHeader(hdr_path)),
      data_path_(findEnviDataFile(hdr_path)),
      mode_(mode),
      swap_bytes_(enviNeedsByteSwap(header_.byte_order)),
      value_bytes_(bytesPerValue(header_.data_type)),
      line_values_(static_cast<std::size_t>(header_.bands) * static_cast<std::size_t>(header_.samples)),
      line_bytes_(line_values_ * value_bytes_),
      row_bytes_(static_cast<std::size_t>(header_.samples) * value_bytes_) {
  std::uint64_t size = 0;
  if (mode_ == EnviReadMode::mapped) {
    // Sequential read-ahead suits BIL/BIP; BSQ reads one row in each of the
    // band planes, which is B interleaved streams, not one.
    map_ = std::make_unique<MappedFile>(data_path_, header_.interleave == EnviInterleave::bsq
                                                        ? MappedFile::Access::normal
                                                        : MappedFile::Access::sequential);
    size = map_->size();
  } else {
    file_ = std::make_unique<PositionedFile>(data_path_, header_.interleave == EnviInterleave::bsq
                                                             ? PositionedFile::Access::normal
                                                             : PositionedFile::Access::sequential);
    size = file_->size();
  }
  const std::uint64_t needed = header_.header_offset + header_.dataBytes();
  if (size < needed) {
    throw InputError(
        data_path_, "",
        "truncated: expected at least " + std::to_string(needed) + " bytes (header offset " +
            std::to_string(header_.header_offset) + " + " + std::to_string(header_.samples) +
            " samples x " + std::to_string(header_.lines) + " lines x " +
            std::to_string(header_.bands) + " bands x " + std::to_string(value_bytes_) +
            " bytes), found " + std::to_string(size));
  }
  std::size_t window_bytes = kReleaseBatchBytes;
  if (mode_ == EnviReadMode::buffered) {
    window_bytes = header_.interleave == EnviInterleave::bsq ? kPlaneWindowBytes : kLineWindowBytes;
  }
  window_lines_ = static_cast<int>(
      std::clamp<std::size_t>(window_bytes / line_bytes_, 1, static_cast<std::size_t>(header_.lines)));
}

void EnviReader::readLine(int line, Eigen::MatrixXf& out) const {
  // Eigen's column-major (b, s) is at b + s * bands, i.e. pixel-major; read
  // band-major into a reused buffer and let Eigen transpose the layout.
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  thread_local std::vector<float> band_major;
  band_major.resize(line_values_);
  readLine(line, band_major.data());
  out = Eigen::Map<const RowMajor>(band_major.data(), header_.bands, header_.samples);
}

void EnviReader::readLine(int line, float* out) const { read(line, EnviLineLayout::band_major, out); }

void EnviReader::readLinePixelMajor(int line, float* out) const { read(line, EnviLineLayout::pixel_major, out); }

void EnviReader::read(int line, EnviLineLayout layout, float* out) const {
  if (line < 0 || line >= header_.lines) {
    throw std::out_of_range("EnviReader: line " + std::to_string(line) + " outside [0, " +
                            std::to_string(header_.lines) + ") of " + hdr_path_.string());
  }
  if (mode_ == EnviReadMode::mapped) {
    readMapped(line, layout, out);
  } else {
    readBuffered(line, layout, out);
  }
}

void EnviReader::readBuffered(int line, EnviLineLayout layout, float* out) const {
  const std::lock_guard<std::mutex> lock(window_mutex_);
  if (line < window_first_ || line >= window_first_ + window_count_) {
    // Sequential reading gets a whole window; a jump gets only its line, so
    // random access does not pay for bytes it will not use.
    const bool sequential = line == last_line_ + 1;
    const int count = sequential ? std::min(window_lines_, header_.lines - line) : 1;
    window_.resize(static_cast<std::size_t>(count) * line_bytes_);
    if (header_.interleave == EnviInterleave::bsq) {
      // Window layout: band b's rows [line, line + count) at b * count * row.
      const std::uint64_t plane_bytes = static_cast<std::uint64_t>(header_.lines) * row_bytes_;
      for (int b = 0; b < header_.bands; ++b) {
        file_->readAt(header_.header_offset + b * plane_bytes + static_cast<std::uint64_t>(line) * row_bytes_,
                      window_.data() + static_cast<std::size_t>(b) * count * row_bytes_, count * row_bytes_);
      }
    } else {
      file_->readAt(header_.header_offset + static_cast<std::uint64_t>(line) * line_bytes_, window_.data(),
                    window_.size());
    }
    window_first_ = line;
    window_count_ = count;
  }
  last_line_ = line;
  const std::size_t k = static_cast<std::size_t>(line - window_first_);
  if (header_.interleave == EnviInterleave::bsq) {
    decodeLine(window_.data() + k * row_bytes_, static_cast<std::size_t>(window_count_) * row_bytes_, layout, out);
  } else {
    decodeLine(window_.data() + k * line_bytes_, 0, layout, out);
  }
}

void EnviReader::readMapped(int line, EnviLineLayout layout, float* out) const {
  const std::byte* base = map_->data() + header_.header_offset;
  if (header_.interleave == EnviInterleave::bsq) {
    decodeLine(base + static_cast<std::size_t>(line) * row_bytes_,
               static_cast<std::size_t>(header_.lines) * row_bytes_, layout, out);
  } else {
    decodeLine(base + static_cast<std::size_t>(line) * line_bytes_, 0, layout, out);
  }
  releaseBehind(line);
}

void EnviReader::decodeLine(const std::byte* start, std::size_t band_stride, EnviLineLayout layout,
                            float* out) const {
  const std::size_t samples = static_cast<std::size_t>(header_.samples);
  const std::size_t bands = static_cast<std::size_t>(header_.bands);
  const bool pixel_major = layout == EnviLineLayout::pixel_major;
  switch (header_.interleave) {
    case EnviInterleave::bil:
      if (pixel_major) {
        // The line's B rows of S values, transposed: the same kernel as BIP's
        // with the roles of rows and columns swapped.
        decodeSamplesTransposed(header_.data_type, swap_bytes_, start, bands, samples, out, bands);
      } else {
        // A BIL line is already band-major.
        decodeSamples(header_.data_type, swap_bytes_, start, out, line_values_);
      }
      break;
    case EnviInterleave::bsq: {
      thread_local std::vector<float> band_major;
      float* rows = out;
      if (pixel_major) {
        band_major.resize(line_values_);
        rows = band_major.data();
      }
      for (std::size_t b = 0; b < bands; ++b) {
        decodeSamples(header_.data_type, swap_bytes_, start + b * band_stride, rows + b * samples, samples);
      }
      if (pixel_major) transposeFloats(rows, bands, samples, samples, out, bands);
      break;
    }
    case EnviInterleave::bip:
      if (pixel_major) {
        decodeSamples(header_.data_type, swap_bytes_, start, out, line_values_);
      } else {
        decodeSamplesTransposed(header_.data_type, swap_bytes_, start, samples, bands, out, samples);
      }
      break;
  }
}

void EnviReader::releaseBehind(int line) const {
  int released = released_lines_.load(std::memory_order_relaxed);
  if (line - released < window_lines_) return;  // also: reading backwards
  if (!released_lines_.compare_exchange_strong(released, line, std::memory_order_relaxed)) return;
  if (header_.interleave == EnviInterleave::bsq) {
    // The cursor is in every band plane at once. One call for the whole map
    // rather than one per plane: each madvise costs a TLB flush (~0.5 ms on
    // the project's VM, so 211 calls per batch dominated the read); the rows
    // in use simply fault back in.
    map_->release(0, map_->size());
    return;
  }
  // Lines [released, line) are behind the cursor; the current one stays.
  // The kernel maps pages around each fault ("fault-around", 64 KB by
  // default), which can bring back pages just behind an earlier release, so
  // each release reaches back a margin over the previous one.
  constexpr std::size_t kFaultAroundMargin = 256u << 10;
  const std::size_t floor = header_.header_offset;
  const std::size_t end = floor + static_cast<std::size_t>(line) * line_bytes_;
  std::size_t begin = floor + static_cast<std::size_t>(released) * line_bytes_;
  begin = begin >= floor + kFaultAroundMargin ? begin - kFaultAroundMargin : floor;
  map_->release(begin, end - begin);
}

}  // namespace hsmap
