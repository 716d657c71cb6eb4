// markInvalidSamples: which samples of a line are left out, by data type.
#include "pipelines/products/spectrum_validity.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

namespace hsmap {
namespace {

constexpr int kBands = 5, kSamples = 4;

// Sample 1 holds a NaN, sample 2 an infinity, sample 3 the value 7 in one band.
std::vector<float> spoiledLine() {
  std::vector<float> line(kBands * kSamples, 1.0f);
  line[1 * kBands + 2] = std::numeric_limits<float>::quiet_NaN();
  line[2 * kBands + 4] = -std::numeric_limits<float>::infinity();
  line[3 * kBands + 0] = 7.0f;
  return line;
}

TEST(MarkInvalidSamples, AFloatCubesNaNAndInfinityAreNonFiniteAndItsIgnoreValueIgnored) {
  const std::vector<float> line = spoiledLine();
  std::vector<std::uint8_t> non_finite(kSamples, 9), ignored(kSamples, 9);
  markInvalidSamples(line.data(), kBands, kSamples, EnviDataType::float32, 7.0f, non_finite.data(), ignored.data());
  EXPECT_EQ(non_finite, (std::vector<std::uint8_t>{0, 1, 1, 0}));
  EXPECT_EQ(ignored, (std::vector<std::uint8_t>{0, 0, 0, 1}));
}

TEST(MarkInvalidSamples, WithoutAnIgnoreValueNothingIsIgnored) {
  const std::vector<float> line = spoiledLine();
  std::vector<std::uint8_t> non_finite(kSamples, 9), ignored(kSamples, 9);
  markInvalidSamples(line.data(), kBands, kSamples, EnviDataType::float64, std::nullopt, non_finite.data(),
                     ignored.data());
  EXPECT_EQ(non_finite, (std::vector<std::uint8_t>{0, 1, 1, 0}));
  EXPECT_EQ(ignored, (std::vector<std::uint8_t>(kSamples, 0)));
}

// An integer cube decodes to finite values only, so its values are not
// scanned for NaN; its ignore value still applies.
TEST(MarkInvalidSamples, AnIntegerCubeIsCheckedForItsIgnoreValueOnly) {
  std::vector<float> line(kBands * kSamples, 100.0f);
  line[2 * kBands + 1] = 65535.0f;
  for (EnviDataType type : {EnviDataType::uint8, EnviDataType::int16, EnviDataType::uint16, EnviDataType::int32,
                            EnviDataType::uint32}) {
    std::vector<std::uint8_t> non_finite(kSamples, 9), ignored(kSamples, 9);
    markInvalidSamples(line.data(), kBands, kSamples, type, 65535.0f, non_finite.data(), ignored.data());
    EXPECT_EQ(non_finite, (std::vector<std::uint8_t>(kSamples, 0)));
    EXPECT_EQ(ignored, (std::vector<std::uint8_t>{0, 0, 1, 0}));
    markInvalidSamples(line.data(), kBands, kSamples, type, std::nullopt, non_finite.data(), ignored.data());
    EXPECT_EQ(ignored, (std::vector<std::uint8_t>(kSamples, 0)));
  }
}

}  // namespace
}  // namespace hsmap
