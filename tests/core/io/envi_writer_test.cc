#include "core/io/envi_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/envi_reader.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

constexpr int kSamples = 5, kLines = 4, kBands = 3;

// Values with a fractional part, so that the rounding of integer types is
// exercised, and negative ones for the signed types.
float sourceValue(int l, int b, int s, bool is_signed) {
  const float value = static_cast<float>(l * 15 + b * 5 + s) + 0.25f;
  return is_signed && (l + s) % 2 == 1 ? -value : value;
}

bool isSigned(EnviDataType type) {
  return type == EnviDataType::int16 || type == EnviDataType::int32 || type == EnviDataType::float32 ||
         type == EnviDataType::float64;
}
bool isFloat(EnviDataType type) { return type == EnviDataType::float32 || type == EnviDataType::float64; }

using RoundTripCase = std::tuple<EnviInterleave, EnviDataType, int>;

class EnviRoundTrip : public ::testing::TestWithParam<RoundTripCase> {};

TEST_P(EnviRoundTrip, WriterThenReaderGivesTheLinesBack) {
  const auto [interleave, type, byte_order] = GetParam();
  TempFolder dir;
  EnviHeader header;
  header.samples = kSamples;
  header.lines = kLines;
  header.bands = kBands;
  header.data_type = type;
  header.interleave = interleave;
  header.byte_order = byte_order;
  header.header_offset = byte_order == 1 ? 7 : 0;  // an odd offset: unaligned values
  header.wavelength = {450, 550, 650};
  EnviWriter writer(dir / "cube.hdr", header);
  std::vector<float> line(kSamples * kBands);
  for (int l = 0; l < kLines; ++l) {
    for (int b = 0; b < kBands; ++b) {
      for (int s = 0; s < kSamples; ++s) line[b * kSamples + s] = sourceValue(l, b, s, isSigned(type));
    }
    writer.writeLine(line.data());
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "cube.raw"));
  EXPECT_TRUE(std::filesystem::exists(dir / "cube.raw.partial"));
  writer.finish();
  EXPECT_FALSE(std::filesystem::exists(dir / "cube.raw.partial"));
  EXPECT_EQ(std::filesystem::file_size(dir / "cube.raw"), header.header_offset + header.dataBytes());

  const EnviReader reader(dir / "cube.hdr");
  const EnviReader mapped(dir / "cube.hdr", EnviReadMode::mapped);
  EXPECT_EQ(reader.header(), header);
  for (int l = 0; l < kLines; ++l) {
    std::vector<float> mapped_line(line.size());
    mapped.readLine(l, mapped_line.data());
    reader.readLine(l, line.data());
    EXPECT_EQ(mapped_line, line) << "line " << l;
    for (int b = 0; b < kBands; ++b) {
      for (int s = 0; s < kSamples; ++s) {
        const float source = sourceValue(l, b, s, isSigned(type));
        const float expected = isFloat(type) ? source : std::round(source);
        EXPECT_EQ(line[b * kSamples + s], expected) << "line " << l << " band " << b << " sample " << s;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryLayout, EnviRoundTrip,
    ::testing::Combine(::testing::Values(EnviInterleave::bsq, EnviInterleave::bil, EnviInterleave::bip),
                       ::testing::Values(EnviDataType::uint8, EnviDataType::int16, EnviDataType::int32,
                                         EnviDataType::float32, EnviDataType::float64, EnviDataType::uint16,
                                         EnviDataType::uint32),
                       ::testing::Values(0, 1)),
    [](const ::testing::TestParamInfo<RoundTripCase>& info) {
      return std::string(toString(std::get<0>(info.param))) + "_" + toString(std::get<1>(info.param)) +
             (std::get<2>(info.param) == 1 ? "_big" : "_little");
    });

// The bytes themselves, checked without the reader.
TEST(EnviWriter, BsqUint8BytesArePlanesOfRows) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 2;
  header.lines = 2;
  header.bands = 2;
  header.data_type = EnviDataType::uint8;
  header.interleave = EnviInterleave::bsq;
  EnviWriter writer(dir / "q.hdr", header);
  const float line0[] = {1, 2, 11, 12};  // band 0: 1 2, band 1: 11 12
  const float line1[] = {3, 4, 13, 14};
  writer.writeLine(line0);
  writer.writeLine(line1);
  writer.finish();
  EXPECT_EQ(TempFolder::read(dir / "q.raw"), std::string({1, 2, 3, 4, 11, 12, 13, 14}));
}

TEST(EnviWriter, BipUint16BigEndianBytesArePixelsOfBands) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 2;
  header.lines = 1;
  header.bands = 2;
  header.data_type = EnviDataType::uint16;
  header.interleave = EnviInterleave::bip;
  header.byte_order = 1;
  header.header_offset = 2;
  EnviWriter writer(dir / "p.hdr", header);
  const float line[] = {0x0102, 0x0304, 0x0a0b, 0x0c0d};  // band 0: s0 s1, band 1: s0 s1
  writer.writeLine(line);
  writer.finish();
  EXPECT_EQ(TempFolder::read(dir / "p.raw"), std::string({0, 0, 1, 2, 10, 11, 3, 4, 12, 13}));
}

TEST(EnviWriter, UnfinishedWriterLeavesNothingBehind) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 2;
  header.lines = 3;
  header.bands = 1;
  {
    EnviWriter writer(dir / "c.hdr", header);
    const float line[] = {1, 2};
    writer.writeLine(line);
    EXPECT_THROW(writer.finish(), std::logic_error);  // 1 of 3 lines
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(EnviWriter, RejectsExtraLinesAndCountsLinesWhenAskedTo) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 2;
  header.lines = 1;
  header.bands = 1;
  header.interleave = EnviInterleave::bil;
  const float line[] = {1, 2};
  {
    EnviWriter writer(dir / "one.hdr", header);
    writer.writeLine(line);
    EXPECT_THROW(writer.writeLine(line), std::logic_error);
  }
  header.lines = 0;  // count as written
  EnviWriter writer(dir / "n.hdr", header);
  for (int i = 0; i < 3; ++i) writer.writeLine(line);
  writer.finish();
  EXPECT_EQ(readEnviHeader(dir / "n.hdr").lines, 3);

  header.interleave = EnviInterleave::bsq;  // BSQ cannot count
  EXPECT_THROW(EnviWriter(dir / "b.hdr", header), std::invalid_argument);
  header.lines = 1;
  EXPECT_THROW(EnviWriter(dir / "b.raw", header), std::invalid_argument);  // not .hdr
}

TEST(EnviWriter, DirectModeWritesTheSameBytesAsBuffered) {
  // Lines of an odd size (not whole 4 KB blocks) and a file of several 32 MB
  // direct chunks, so that blocks are cut mid-line, both staging buffers take
  // turns with a write in the background, and the tail is partial.
  TempFolder dir;
  for (const EnviInterleave interleave : {EnviInterleave::bil, EnviInterleave::bip}) {
    EnviHeader header;
    header.samples = 997;
    header.bands = 37;
    header.lines = 500;
    header.data_type = EnviDataType::float32;
    header.interleave = interleave;
    EnviWriter buffered(dir / "buffered.hdr", header);
    EnviWriter direct(dir / "direct.hdr", header, EnviWriteMode::direct);
    std::vector<float> line(std::size_t(header.samples) * header.bands);
    for (int l = 0; l < header.lines; ++l) {
      for (std::size_t i = 0; i < line.size(); ++i) line[i] = float(l) * 1e-3f + float(i);
      buffered.writeLine(line.data());
      direct.writeLine(line.data());
    }
    buffered.finish();
    direct.finish();
    const std::string a = TempFolder::read(dir / "buffered.raw");
    const std::string b = TempFolder::read(dir / "direct.raw");
    ASSERT_EQ(a.size(), std::size_t(header.lines) * line.size() * 4);
    EXPECT_TRUE(a == b) << "interleave " << int(interleave)
                        << (direct.direct() ? ", O_DIRECT" : ", buffered fallback");
    EXPECT_EQ(TempFolder::read(dir / "buffered.hdr"), TempFolder::read(dir / "direct.hdr"));
  }
}

TEST(EnviWriter, LinesFilledInPlaceAreTheSameBytesAsWrittenLines) {
  // writeLineWith() fills the staging buffer itself where the file takes
  // floats as they are (direct, BIL, native float32) and a scratch line
  // otherwise; either way the file must match writeLine()'s, NaN included.
  // 300 lines of 997 x 37 floats span several 32 MB chunks.
  TempFolder dir;
  struct Case {
    EnviInterleave interleave;
    EnviDataType type;
    int byte_order;  // 0 little, 1 big endian
    EnviWriteMode mode;
  };
  const Case cases[] = {
      {EnviInterleave::bil, EnviDataType::float32, 0, EnviWriteMode::direct},
      {EnviInterleave::bil, EnviDataType::float32, 1, EnviWriteMode::direct},
      {EnviInterleave::bip, EnviDataType::float32, 0, EnviWriteMode::direct},
      {EnviInterleave::bil, EnviDataType::int16, 0, EnviWriteMode::direct},
      {EnviInterleave::bsq, EnviDataType::float32, 0, EnviWriteMode::buffered},
  };
  for (const Case& c : cases) {
    EnviHeader header;
    header.samples = 997;
    header.bands = 37;
    header.lines = 300;
    header.data_type = c.type;
    header.byte_order = c.byte_order;
    header.interleave = c.interleave;
    EnviWriter written(dir / "written.hdr", header, c.mode);
    EnviWriter filled(dir / "filled.hdr", header, c.mode);
    std::vector<float> line(std::size_t(header.samples) * header.bands);
    for (int l = 0; l < header.lines; ++l) {
      for (std::size_t i = 0; i < line.size(); ++i) line[i] = float(l) * 1e-3f + float(i % 5000) - 2000.0f;
      line[std::size_t(l) % line.size()] = std::numeric_limits<float>::quiet_NaN();
      written.writeLine(line.data());
      filled.writeLineWith([&](float* out) { std::copy(line.begin(), line.end(), out); });
    }
    EXPECT_THROW(filled.writeLineWith([](float*) {}), std::logic_error);
    written.finish();
    filled.finish();
    const std::string a = TempFolder::read(dir / "written.raw");
    const std::string b = TempFolder::read(dir / "filled.raw");
    ASSERT_EQ(a.size(), std::size_t(header.lines) * line.size() * bytesPerValue(c.type));
    EXPECT_TRUE(a == b) << "interleave " << int(c.interleave) << ", type " << int(c.type) << ", byte order "
                        << c.byte_order << (filled.direct() ? ", O_DIRECT" : ", buffered");
  }
}

TEST(EnviWriter, DirectWriterAbandonedMidWriteLeavesNothing) {
  // Destroyed with a chunk still being written in the background: the write
  // ends, then the partial file goes; no data file, no header.
  TempFolder dir;
  EnviHeader header;
  header.samples = 1024;
  header.bands = 64;
  header.lines = 400;
  header.data_type = EnviDataType::float32;
  {
    EnviWriter writer(dir / "cut.hdr", header, EnviWriteMode::direct);
    const std::vector<float> line(std::size_t(header.samples) * header.bands, 1.5f);
    for (int l = 0; l < 200; ++l) writer.writeLine(line.data());  // 50 MB: one chunk handed over
    EXPECT_TRUE(std::filesystem::exists(dir / "cut.raw.partial"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "cut.raw.partial"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cut.raw"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cut.hdr"));
}

TEST(EnviWriter, EigenLineMatchesPointerLine) {
  TempFolder dir;
  EnviHeader header;
  header.samples = 3;
  header.lines = 1;
  header.bands = 2;
  EnviWriter writer(dir / "e.hdr", header);
  Eigen::MatrixXf line(2, 3);
  line << 1, 2, 3, 4, 5, 6;
  writer.writeLine(line);
  writer.finish();
  const EnviReader reader(dir / "e.hdr");
  Eigen::MatrixXf back;
  reader.readLine(0, back);
  EXPECT_EQ(back, line);
  EXPECT_THROW(EnviWriter(dir / "f.hdr", header).writeLine(Eigen::MatrixXf(3, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
