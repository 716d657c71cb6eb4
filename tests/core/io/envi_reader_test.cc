#include "core/io/envi_reader.h"

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/envi_writer.h"
#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

// A cube written byte by byte, independently of EnviWriter: 3 samples x
// 2 lines x 2 bands, int16 big endian, BIP, after a 5-byte header offset.
// v(l, b, s) = -300 + 100 l + 10 b + s covers negative values.
float expectedValue(int l, int b, int s) { return static_cast<float>(-300 + 100 * l + 10 * b + s); }

std::filesystem::path writeHandMadeBipCube(const TempFolder& dir, bool truncate = false) {
  dir.write("cube.hdr",
            "ENVI\nsamples = 3\nlines = 2\nbands = 2\nheader offset = 5\n"
            "data type = 2\ninterleave = bip\nbyte order = 1\n");
  std::string bytes = "HSMAP";  // the header offset: skipped by the reader
  for (int l = 0; l < 2; ++l) {
    for (int s = 0; s < 3; ++s) {
      for (int b = 0; b < 2; ++b) {
        const auto value = static_cast<std::uint16_t>(static_cast<std::int16_t>(expectedValue(l, b, s)));
        bytes += static_cast<char>(value >> 8);    // big endian: high byte first
        bytes += static_cast<char>(value & 0xff);
      }
    }
  }
  if (truncate) bytes.pop_back();
  dir.write("cube.raw", bytes);
  return dir / "cube.hdr";
}

class EnviReaderModes : public ::testing::TestWithParam<EnviReadMode> {};

TEST_P(EnviReaderModes, ReadsAHandWrittenBigEndianBipCubeWithHeaderOffset) {
  TempFolder dir;
  const EnviReader reader(writeHandMadeBipCube(dir), GetParam());
  EXPECT_EQ(reader.dataPath(), dir / "cube.raw");
  std::vector<float> line(6);
  for (int l = 0; l < 2; ++l) {
    reader.readLine(l, line.data());
    for (int b = 0; b < 2; ++b) {
      for (int s = 0; s < 3; ++s) {
        EXPECT_EQ(line[b * 3 + s], expectedValue(l, b, s)) << "line " << l << " band " << b << " sample " << s;
      }
    }
  }
  Eigen::MatrixXf matrix;
  reader.readLine(1, matrix);
  ASSERT_EQ(matrix.rows(), 2);
  ASSERT_EQ(matrix.cols(), 3);
  for (int b = 0; b < 2; ++b) {
    for (int s = 0; s < 3; ++s) EXPECT_EQ(matrix(b, s), expectedValue(1, b, s));
  }
  EXPECT_THROW(reader.readLine(2, line.data()), std::out_of_range);
  EXPECT_THROW(reader.readLine(-1, line.data()), std::out_of_range);
}

TEST_P(EnviReaderModes, ReadsAHandWrittenLittleEndianBsqFloat64Cube) {
  TempFolder dir;
  dir.write("plane.hdr", "ENVI\nsamples = 2\nlines = 3\nbands = 2\ndata type = 5\ninterleave = bsq\n");
  std::string bytes;
  for (int b = 0; b < 2; ++b) {
    for (int l = 0; l < 3; ++l) {
      for (int s = 0; s < 2; ++s) {
        const double value = 0.5 * (100 * b + 10 * l + s);
        bytes.append(reinterpret_cast<const char*>(&value), sizeof value);  // this host is little endian
      }
    }
  }
  dir.write("plane.img", bytes);
  const EnviReader reader(dir / "plane.hdr", GetParam());
  std::vector<float> line(4);
  reader.readLine(2, line.data());
  EXPECT_EQ(line, (std::vector<float>{10.0f, 10.5f, 60.0f, 60.5f}));
}

TEST_P(EnviReaderModes, TruncatedDataFileNamesTheFileAndTheSizes) {
  TempFolder dir;
  const auto hdr = writeHandMadeBipCube(dir, /*truncate=*/true);
  try {
    EnviReader reader(hdr, GetParam());
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              (dir / "cube.raw").string() +
                  ": truncated: expected at least 29 bytes (header offset 5 + 3 samples x 2 lines x "
                  "2 bands x 2 bytes), found 28");
    EXPECT_EQ(error.file(), dir / "cube.raw");
  }
}

INSTANTIATE_TEST_SUITE_P(BothModes, EnviReaderModes,
                         ::testing::Values(EnviReadMode::buffered, EnviReadMode::mapped),
                         [](const ::testing::TestParamInfo<EnviReadMode>& info) {
                           return std::string(info.param == EnviReadMode::buffered ? "buffered" : "mapped");
                         });

TEST(EnviReader, MissingDataFileIsAnInputError) {
  TempFolder dir;
  writeHandMadeBipCube(dir);
  std::filesystem::remove(dir / "cube.raw");
  EXPECT_THROW(EnviReader reader(dir / "cube.hdr"), InputError);
}

long statusKilobytes(const char* field) {
  std::ifstream status("/proc/self/status");
  const std::string prefix = std::string(field) + ":";
  for (std::string line; std::getline(status, line);) {
    if (line.rfind(prefix, 0) == 0) return std::stol(line.substr(prefix.size()));
  }
  return -1;
}

// A 32 MB cube, several buffered windows and mapped release batches long.
constexpr int kBigSamples = 256, kBigBands = 64, kBigLines = 1024;
float bigValue(int l, int b, int s) { return static_cast<float>((l * 131 + b * 31 + s * 7) % 4093); }

std::filesystem::path writeBigCube(const TempFolder& dir, EnviInterleave interleave) {
  EnviHeader header;
  header.samples = kBigSamples;
  header.bands = kBigBands;
  header.lines = kBigLines;
  header.data_type = EnviDataType::uint16;
  header.interleave = interleave;
  header.header_offset = 3;
  const auto hdr = dir / (std::string("big_") + toString(interleave) + ".hdr");
  EnviWriter writer(hdr, header);
  std::vector<float> line(kBigSamples * kBigBands);
  for (int l = 0; l < kBigLines; ++l) {
    for (int b = 0; b < kBigBands; ++b) {
      for (int s = 0; s < kBigSamples; ++s) line[b * kBigSamples + s] = bigValue(l, b, s);
    }
    writer.writeLine(line.data());
  }
  writer.finish();
  return hdr;
}

void expectBigLine(const std::vector<float>& line, int l) {
  for (int b = 0; b < kBigBands; ++b) {
    for (int s = 0; s < kBigSamples; ++s) {
      if (line[b * kBigSamples + s] != bigValue(l, b, s)) {
        FAIL() << "line " << l << " band " << b << " sample " << s << ": " << line[b * kBigSamples + s]
               << " != " << bigValue(l, b, s);
      }
    }
  }
}

// readLinePixelMajor gives out[s * B + b] in every interleave, data type,
// byte order and mode: each 16-bit BIL line goes through the fused
// convert-and-transpose kernel with its rows and columns swapped, so sizes
// that are not multiples of its 4 x 4 blocks and 16-row passes are included.
TEST(EnviReader, PixelMajorLinesHoldEachSamplesSpectrum) {
  TempFolder dir;
  const auto value = [](int l, int b, int s) { return static_cast<float>((l * 37 + b * 11 + s * 5) % 611 - 300); };
  for (const auto& [samples, bands] : {std::pair{37, 13}, std::pair{97, 211}}) {
    for (const EnviInterleave interleave : {EnviInterleave::bil, EnviInterleave::bip, EnviInterleave::bsq}) {
      for (const EnviDataType type : {EnviDataType::int16, EnviDataType::uint16, EnviDataType::float32,
                                      EnviDataType::float64}) {
        for (const int byte_order : {0, 1}) {
          EnviHeader header;
          header.samples = samples;
          header.bands = bands;
          header.lines = 5;
          header.data_type = type;
          header.byte_order = byte_order;
          header.interleave = interleave;
          const auto hdr = dir / "pixel_major.hdr";
          {
            EnviWriter writer(hdr, header);
            std::vector<float> line(std::size_t(samples) * bands);
            for (int l = 0; l < header.lines; ++l) {
              for (int b = 0; b < bands; ++b) {
                for (int s = 0; s < samples; ++s) {
                  const float v = value(l, b, s);
                  line[std::size_t(b) * samples + s] = type == EnviDataType::uint16 ? v + 300.0f : v;
                }
              }
              writer.writeLine(line.data());
            }
            writer.finish();
          }
          for (const EnviReadMode mode : {EnviReadMode::buffered, EnviReadMode::mapped}) {
            const EnviReader reader(hdr, mode);
            std::vector<float> out(std::size_t(samples) * bands);
            for (const int l : {0, 1, 2, 4, 3}) {
              reader.readLinePixelMajor(l, out.data());
              int wrong = 0;
              for (int s = 0; s < samples; ++s) {
                for (int b = 0; b < bands; ++b) {
                  const float expected = value(l, b, s) + (type == EnviDataType::uint16 ? 300.0f : 0.0f);
                  wrong += out[std::size_t(s) * bands + b] != expected;
                }
              }
              EXPECT_EQ(wrong, 0) << samples << " x " << bands << ", interleave " << toString(interleave)
                                  << ", type " << int(type) << ", byte order " << byte_order << ", "
                                  << (mode == EnviReadMode::buffered ? "buffered" : "mapped") << ", line " << l;
            }
          }
        }
      }
    }
  }
}

// Sequential passes, jumps back and forth, window boundaries: both ways of
// reading give every value, for the layout with the most bookkeeping (BSQ).
TEST(EnviReader, BufferedAndMappedReadEveryLineInAnyOrder) {
  TempFolder dir;
  const auto hdr = writeBigCube(dir, EnviInterleave::bsq);
  for (const EnviReadMode mode : {EnviReadMode::buffered, EnviReadMode::mapped}) {
    SCOPED_TRACE(mode == EnviReadMode::buffered ? "buffered" : "mapped");
    const EnviReader reader(hdr, mode);
    std::vector<float> line(kBigSamples * kBigBands);
    for (int l = 0; l < kBigLines; ++l) {
      reader.readLine(l, line.data());
      expectBigLine(line, l);
    }
    for (const int l : {1000, 3, 4, 5, 600, 511, 512, 513, 0, 1023, 1022, 700, 701}) {
      reader.readLine(l, line.data());
      expectBigLine(line, l);
    }
  }
}

// Streaming in order must not keep the cube in memory: the mapped reader
// drops pages behind the cursor every 16 MB, the buffered one never maps the
// file and reuses a 16 MB window.
TEST(EnviReader, SequentialReadingKeepsMemoryBounded) {
  TempFolder dir;
  const auto hdr = writeBigCube(dir, EnviInterleave::bil);
  for (const EnviReadMode mode : {EnviReadMode::mapped, EnviReadMode::buffered}) {
    SCOPED_TRACE(mode == EnviReadMode::buffered ? "buffered" : "mapped");
    const long file_before = statusKilobytes("RssFile");
    const long anon_before = statusKilobytes("RssAnon");
    ASSERT_GE(file_before, 0) << "no RssFile in /proc/self/status";
    long file_peak = file_before, anon_peak = anon_before;
    {
      const EnviReader reader(hdr, mode);
      std::vector<float> line(kBigSamples * kBigBands);
      for (int l = 0; l < kBigLines; ++l) {
        reader.readLine(l, line.data());
        ASSERT_EQ(line[77], bigValue(l, 0, 77));
        file_peak = std::max(file_peak, statusKilobytes("RssFile"));
        anon_peak = std::max(anon_peak, statusKilobytes("RssAnon"));
      }
    }
    // 32 MB would stay mapped without release; the batch/window is 16 MB.
    EXPECT_LT(file_peak - file_before, 24 * 1024) << "peak RssFile growth " << (file_peak - file_before) << " kB";
    EXPECT_LT(anon_peak - anon_before, 24 * 1024) << "peak RssAnon growth " << (anon_peak - anon_before) << " kB";
  }
}

}  // namespace
}  // namespace hsmap
