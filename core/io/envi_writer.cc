#include "core/io/envi_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/io/atomic_file.h"
#include "core/io/envi_sample_codec.h"
#include "core/io/float_transpose.h"

namespace hsmap {

namespace {
// O_DIRECT transfers: offsets, sizes and buffers aligned to this (the page
// size, a multiple of every common logical block size).
constexpr std::size_t kDirectAlignment = 4096;
// Bytes per direct write: large enough to keep the device busy.
constexpr std::size_t kDirectChunk = std::size_t(32) << 20;
}  // namespace

EnviWriter::EnviWriter(const std::filesystem::path& hdr_path, EnviHeader header, EnviWriteMode mode)
    : hdr_path_(hdr_path), header_(std::move(header)) {
  if (hdr_path_.extension() != ".hdr") {
    throw std::invalid_argument("EnviWriter: header path must end in .hdr, got " + hdr_path_.string());
  }
  data_path_ = hdr_path_;
  data_path_.replace_extension(".raw");
  partial_path_ = AtomicFile::partialPathFor(data_path_);
  if (header_.samples <= 0 || header_.bands <= 0 || header_.lines < 0) {
    throw std::invalid_argument("EnviWriter " + hdr_path_.string() +
                                ": samples and bands must be positive and lines non-negative");
  }
  count_lines_ = header_.lines == 0;
  if (count_lines_ && header_.interleave == EnviInterleave::bsq) {
    throw std::invalid_argument("EnviWriter " + hdr_path_.string() +
                                ": BSQ needs the number of lines up front (lines = 0 given)");
  }
  // Validate the rest of the header now rather than after hours of writing:
  // the header's own checks run on a copy with a provisional line count.
  {
    EnviHeader probe = header_;
    probe.lines = std::max(1, probe.lines);
    formatEnviHeader(probe);
  }
  value_bytes_ = bytesPerValue(header_.data_type);
  swap_bytes_ = enviNeedsByteSwap(header_.byte_order);

  std::error_code ec;
  std::filesystem::remove(partial_path_, ec);
  direct_ = mode == EnviWriteMode::direct && header_.interleave != EnviInterleave::bsq &&
            header_.header_offset == 0;
  if (direct_) {
    fd_ = ::open(partial_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_DIRECT, 0644);
    if (fd_ < 0) direct_ = false;  // e.g. tmpfs: EINVAL; retried below without O_DIRECT
  }
  if (fd_ < 0) fd_ = ::open(partial_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot create " + partial_path_.string() + ": " + std::strerror(errno));
  }
  // The header offset is zero bytes; ftruncate makes them without writing.
  if (header_.header_offset > 0 && ::ftruncate(fd_, static_cast<off_t>(header_.header_offset)) != 0) {
    const int error = errno;
    abandon();
    throw std::runtime_error("cannot write " + partial_path_.string() + ": " + std::strerror(error));
  }
  const std::size_t line_values = static_cast<std::size_t>(header_.samples) * header_.bands;
  line_bytes_ = line_values * value_bytes_;
  if (direct_) {
    // Room for a chunk plus one line and the partial block kept over.
    staging_capacity_ =
        (kDirectChunk + line_bytes_ + 2 * kDirectAlignment) / kDirectAlignment * kDirectAlignment;
    staging_ = {static_cast<std::byte*>(std::aligned_alloc(kDirectAlignment, staging_capacity_)), std::free};
    writing_ = {static_cast<std::byte*>(std::aligned_alloc(kDirectAlignment, staging_capacity_)), std::free};
    if (!staging_ || !writing_) {
      abandon();
      throw std::bad_alloc();
    }
  }
  floats_in_place_ = direct_ && header_.interleave == EnviInterleave::bil &&
                     header_.data_type == EnviDataType::float32 && !swap_bytes_;
  encoded_.resize(line_values * value_bytes_);
  if (header_.interleave == EnviInterleave::bip) pixel_major_.resize(line_values);
}

EnviWriter::~EnviWriter() { abandon(); }

void EnviWriter::abandon() noexcept {
  // The background write uses fd_ and its buffer: it ends before either goes.
  if (pending_write_.valid()) {
    try {
      pending_write_.get();
    } catch (...) {
      // Abandoning anyway: the partial file is removed below.
    }
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!finished_) {
    std::error_code ec;
    std::filesystem::remove(partial_path_, ec);
  }
}

void EnviWriter::writeAt(const std::byte* bytes, std::size_t size, std::size_t offset) {
  while (size > 0) {
    const ssize_t written = ::pwrite(fd_, bytes, size, static_cast<off_t>(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error("writing " + partial_path_.string() + " failed: " + std::strerror(errno));
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
    offset += static_cast<std::size_t>(written);
  }
}

void EnviWriter::writeBlocks(const std::byte* bytes, std::size_t size, std::size_t offset) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t written = ::pwrite(fd_, bytes + done, size - done, static_cast<off_t>(offset + done));
    if (written < 0) {
      if (errno == EINTR) continue;
      if (errno == EINVAL) {
        // The file system took O_DIRECT on open but not for writes: go on buffered.
        const int flags = ::fcntl(fd_, F_GETFL);
        if (flags >= 0 && ::fcntl(fd_, F_SETFL, flags & ~O_DIRECT) == 0) continue;
      }
      throw std::runtime_error("writing " + partial_path_.string() + " failed: " + std::strerror(errno));
    }
    // A short write that stops inside a block makes the next one unaligned:
    // EINVAL, and the rest goes on buffered (above).
    done += static_cast<std::size_t>(written);
  }
}

void EnviWriter::waitForPendingWrite() {
  if (pending_write_.valid()) pending_write_.get();
}

void EnviWriter::flushStagedBlocks() {
  const std::size_t whole = staged_ / kDirectAlignment * kDirectAlignment;
  if (whole == 0) return;
  // The other buffer is free once its write has ended.
  waitForPendingWrite();
  std::memcpy(writing_.get(), staging_.get() + whole, staged_ - whole);
  std::swap(staging_, writing_);
  const std::byte* full = writing_.get();
  const std::size_t offset = staged_offset_;
  pending_write_ = std::async(std::launch::async, [this, full, whole, offset] { writeBlocks(full, whole, offset); });
  staged_ -= whole;
  staged_offset_ += whole;
}

void EnviWriter::writeLine(const Eigen::MatrixXf& line) {
  if (line.rows() != header_.bands || line.cols() != header_.samples) {
    throw std::invalid_argument("EnviWriter::writeLine: expected a " + std::to_string(header_.bands) +
                                " x " + std::to_string(header_.samples) + " matrix, got " +
                                std::to_string(line.rows()) + " x " + std::to_string(line.cols()));
  }
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> band_major = line;
  writeLine(band_major.data());
}

void EnviWriter::checkLineAllowed() const {
  if (finished_ || fd_ < 0) throw std::logic_error("EnviWriter::writeLine after finish()");
  if (!count_lines_ && lines_written_ >= header_.lines) {
    throw std::logic_error("EnviWriter " + hdr_path_.string() + ": the header has " +
                           std::to_string(header_.lines) + " lines, cannot write another");
  }
}

std::byte* EnviWriter::stagedLineSlot() {
  // Appended to the staging buffer (BIL/BIP lines are consecutive).
  if (staged_ + line_bytes_ > staging_capacity_) flushStagedBlocks();
  return staging_.get() + staged_;
}

void EnviWriter::commitStagedLine() {
  staged_ += line_bytes_;
  if (staged_ >= kDirectChunk) flushStagedBlocks();
  ++lines_written_;
}

float* EnviWriter::reserveStagedLine() {
  if (!floats_in_place_) return nullptr;
  checkLineAllowed();
  // Whole lines of 4-byte values from a page-aligned buffer: float-aligned.
  return reinterpret_cast<float*>(stagedLineSlot());
}

void EnviWriter::writeLine(const float* band_major_line) {
  checkLineAllowed();
  const std::size_t samples = static_cast<std::size_t>(header_.samples);
  const std::size_t bands = static_cast<std::size_t>(header_.bands);
  const std::size_t line_values = samples * bands;
  const std::size_t line = static_cast<std::size_t>(lines_written_);
  const std::size_t offset = header_.header_offset;

  if (direct_) {
    std::byte* target = stagedLineSlot();
    if (header_.interleave == EnviInterleave::bip) {
      transposeFloats(band_major_line, bands, samples, samples, pixel_major_.data(), bands);
      encodeSamples(header_.data_type, swap_bytes_, pixel_major_.data(), target, line_values);
    } else {
      encodeSamples(header_.data_type, swap_bytes_, band_major_line, target, line_values);
    }
    commitStagedLine();
    return;
  }

  switch (header_.interleave) {
    case EnviInterleave::bil:
      encodeSamples(header_.data_type, swap_bytes_, band_major_line, encoded_.data(), line_values);
      writeAt(encoded_.data(), line_bytes_, offset + line * line_bytes_);
      break;
    case EnviInterleave::bip:
      transposeFloats(band_major_line, bands, samples, samples, pixel_major_.data(), bands);
      encodeSamples(header_.data_type, swap_bytes_, pixel_major_.data(), encoded_.data(), line_values);
      writeAt(encoded_.data(), line_bytes_, offset + line * line_bytes_);
      break;
    case EnviInterleave::bsq: {
      encodeSamples(header_.data_type, swap_bytes_, band_major_line, encoded_.data(), line_values);
      const std::size_t row_bytes = samples * value_bytes_;
      const std::size_t plane_bytes = static_cast<std::size_t>(header_.lines) * row_bytes;
      for (std::size_t b = 0; b < bands; ++b) {
        writeAt(encoded_.data() + b * row_bytes, row_bytes, offset + b * plane_bytes + line * row_bytes);
      }
      break;
    }
  }
  ++lines_written_;
}

void EnviWriter::finish() {
  if (finished_ || fd_ < 0) throw std::logic_error("EnviWriter::finish called twice");
  if (count_lines_) {
    if (lines_written_ == 0) {
      throw std::logic_error("EnviWriter " + hdr_path_.string() + ": no line written");
    }
    header_.lines = lines_written_;
  } else if (lines_written_ != header_.lines) {
    throw std::logic_error("EnviWriter " + hdr_path_.string() + ": wrote " +
                           std::to_string(lines_written_) + " of " + std::to_string(header_.lines) +
                           " lines");
  }
  if (direct_) {
    flushStagedBlocks();
    waitForPendingWrite();
    if (staged_ > 0) {
      // The last partial block: through the page cache (O_DIRECT needs whole blocks).
      const int flags = ::fcntl(fd_, F_GETFL);
      if (flags < 0 || ::fcntl(fd_, F_SETFL, flags & ~O_DIRECT) != 0) {
        throw std::runtime_error("writing " + partial_path_.string() + " failed: " + std::strerror(errno));
      }
      writeAt(staging_.get(), staged_, staged_offset_);
      staged_offset_ += staged_;
      staged_ = 0;
    }
  }
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) {
    throw std::runtime_error("writing " + partial_path_.string() + " failed: " + std::strerror(errno));
  }
  std::error_code ec;
  std::filesystem::rename(partial_path_, data_path_, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + partial_path_.string() + " to " +
                             data_path_.string() + ": " + ec.message());
  }
  finished_ = true;
  // The header last: once it exists, the data it describes is complete.
  writeEnviHeader(hdr_path_, header_);
}

}  // namespace hsmap
