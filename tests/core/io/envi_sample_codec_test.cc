#include "core/io/envi_sample_codec.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace hsmap {
namespace {

template <typename T>
std::vector<T> encodeAs(EnviDataType type, const std::vector<float>& values) {
  std::vector<T> out(values.size());
  encodeSamples(type, false, values.data(), reinterpret_cast<std::byte*>(out.data()), values.size());
  return out;
}

TEST(EnviSampleCodec, IntegersRoundHalfAwayFromZeroAndClamp) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(encodeAs<std::int16_t>(EnviDataType::int16, {2.5f, -2.5f, 2.49f, 40000.f, -40000.f, nan}),
            (std::vector<std::int16_t>{3, -3, 2, 32767, -32768, 0}));
  EXPECT_EQ(encodeAs<std::uint8_t>(EnviDataType::uint8, {-3.f, 255.4f, 255.6f, 1e9f}),
            (std::vector<std::uint8_t>{0, 255, 255, 255}));
  EXPECT_EQ(encodeAs<std::uint16_t>(EnviDataType::uint16, {65535.4f, 65536.f, -0.4f}),
            (std::vector<std::uint16_t>{65535, 65535, 0}));
  EXPECT_EQ(encodeAs<std::int32_t>(EnviDataType::int32, {3e9f, -3e9f, 123456.5f}),
            (std::vector<std::int32_t>{2147483647, -2147483647 - 1, 123457}));
  EXPECT_EQ(encodeAs<std::uint32_t>(EnviDataType::uint32, {5e9f, -1.f, 16777216.f}),
            (std::vector<std::uint32_t>{4294967295u, 0u, 16777216u}));
}

TEST(EnviSampleCodec, FloatsConvertDirectlyIncludingNaN) {
  const std::vector<double> doubles =
      encodeAs<double>(EnviDataType::float64, {0.1f, -1e30f, std::numeric_limits<float>::quiet_NaN()});
  EXPECT_EQ(doubles[0], static_cast<double>(0.1f));
  EXPECT_EQ(doubles[1], static_cast<double>(-1e30f));
  EXPECT_TRUE(std::isnan(doubles[2]));
}

TEST(EnviSampleCodec, ByteSwapMatchesTheFileOrder) {
  // On this (little endian) host, byte order 1 swaps and 0 does not.
  ASSERT_TRUE(enviNeedsByteSwap(1));
  ASSERT_FALSE(enviNeedsByteSwap(0));
  const float value = 0x0102;
  std::byte bytes[2];
  encodeSamples(EnviDataType::uint16, true, &value, bytes, 1);
  EXPECT_EQ(bytes[0], std::byte{0x01});
  EXPECT_EQ(bytes[1], std::byte{0x02});
  float back = 0;
  decodeSamples(EnviDataType::uint16, true, bytes, &back, 1);
  EXPECT_EQ(back, value);

  const float pi = 3.14159274f;
  std::byte float_bytes[4];
  encodeSamples(EnviDataType::float32, true, &pi, float_bytes, 1);
  std::uint32_t bits;
  std::memcpy(&bits, &pi, 4);
  EXPECT_EQ(float_bytes[0], std::byte(bits >> 24));  // most significant byte first
  decodeSamples(EnviDataType::float32, true, float_bytes, &back, 1);
  EXPECT_EQ(back, pi);
}

TEST(EnviSampleCodec, DecodesUnalignedValues) {
  std::vector<std::byte> buffer(1 + 3 * sizeof(std::int32_t));
  const std::int32_t values[3] = {-7, 65536, 2147483647};
  std::memcpy(buffer.data() + 1, values, sizeof values);  // misaligned by one byte
  float out[3];
  decodeSamples(EnviDataType::int32, false, buffer.data() + 1, out, 3);
  EXPECT_EQ(out[0], -7.f);
  EXPECT_EQ(out[1], 65536.f);
  EXPECT_EQ(out[2], 2147483648.f);  // nearest float
}

// The fused 16-bit path and the tiled path for the other types must both
// equal "decode, then transpose by definition", for shapes around the 4 x 4
// blocks and the 16-band passes, in both byte orders.
TEST(EnviSampleCodec, TransposedDecodingMatchesTheDefinition) {
  const EnviDataType types[] = {EnviDataType::uint8,   EnviDataType::int16,   EnviDataType::int32,
                                EnviDataType::float32, EnviDataType::float64, EnviDataType::uint16,
                                EnviDataType::uint32};
  for (const EnviDataType type : types) {
    for (const bool swap : {false, true}) {
      for (const std::size_t pixels : {1, 3, 4, 5, 9, 130}) {
        for (const std::size_t bands : {1, 3, 4, 5, 16, 17, 21}) {
          // Values that every type holds, negative ones for the signed types.
          const bool is_signed = type == EnviDataType::int16 || type == EnviDataType::int32 ||
                                 type == EnviDataType::float32 || type == EnviDataType::float64;
          std::vector<float> values(pixels * bands);
          for (std::size_t i = 0; i < values.size(); ++i) {
            values[i] = static_cast<float>(i % 251) * (is_signed && i % 3 == 0 ? -1.0f : 1.0f);
          }
          std::vector<std::byte> stored(values.size() * bytesPerValue(type) + 1);
          encodeSamples(type, swap, values.data(), stored.data() + 1, values.size());  // unaligned on purpose
          const std::size_t stride = pixels + 2;
          std::vector<float> out(bands * stride, -7.0f);
          decodeSamplesTransposed(type, swap, stored.data() + 1, pixels, bands, out.data(), stride);
          for (std::size_t b = 0; b < bands; ++b) {
            for (std::size_t p = 0; p < stride; ++p) {
              const float expected = p < pixels ? values[p * bands + b] : -7.0f;  // padding untouched
              ASSERT_EQ(out[b * stride + p], expected)
                  << toString(type) << (swap ? " swapped " : " ") << pixels << "x" << bands << " at band " << b
                  << " pixel " << p;
            }
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace hsmap
