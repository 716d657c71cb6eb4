#include "core/io/envi_sample_codec.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/io/float_transpose.h"

namespace hsmap {
namespace {

// The unsigned integer of the same size, for swapping floats bitwise.
template <typename T>
using Bits = std::conditional_t<sizeof(T) == 1, std::uint8_t,
             std::conditional_t<sizeof(T) == 2, std::uint16_t,
             std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;

template <typename U>
inline U swapBits(U value) {
  if constexpr (sizeof(U) == 1) {
    return value;
  } else if constexpr (sizeof(U) == 2) {
    return __builtin_bswap16(value);
  } else if constexpr (sizeof(U) == 4) {
    return __builtin_bswap32(value);
  } else {
    return __builtin_bswap64(value);
  }
}

template <typename T, bool Swap>
void decodeAs(const std::byte* __restrict src, float* __restrict dst, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    Bits<T> bits;
    std::memcpy(&bits, src + i * sizeof(T), sizeof(T));
    if constexpr (Swap) bits = swapBits(bits);
    dst[i] = static_cast<float>(std::bit_cast<T>(bits));
  }
}

template <typename T>
inline T toStored(float value) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(value);
  } else {
    // double holds every value of these types exactly, so the clamp is exact.
    constexpr double lo = static_cast<double>(std::numeric_limits<T>::lowest());
    constexpr double hi = static_cast<double>(std::numeric_limits<T>::max());
    const double rounded = std::round(static_cast<double>(value));
    if (!(rounded == rounded)) return T(0);  // NaN
    return static_cast<T>(rounded < lo ? lo : (rounded > hi ? hi : rounded));
  }
}

template <typename T, bool Swap>
void encodeAs(const float* __restrict src, std::byte* __restrict dst, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    Bits<T> bits = std::bit_cast<Bits<T>>(toStored<T>(src[i]));
    if constexpr (Swap) bits = swapBits(bits);
    std::memcpy(dst + i * sizeof(T), &bits, sizeof(T));
  }
}

template <bool Swap>
void decodeWith(EnviDataType type, const std::byte* src, float* dst, std::size_t n) {
  switch (type) {
    case EnviDataType::uint8: return decodeAs<std::uint8_t, Swap>(src, dst, n);
    case EnviDataType::int16: return decodeAs<std::int16_t, Swap>(src, dst, n);
    case EnviDataType::int32: return decodeAs<std::int32_t, Swap>(src, dst, n);
    case EnviDataType::float32: return decodeAs<float, Swap>(src, dst, n);
    case EnviDataType::float64: return decodeAs<double, Swap>(src, dst, n);
    case EnviDataType::uint16: return decodeAs<std::uint16_t, Swap>(src, dst, n);
    case EnviDataType::uint32: return decodeAs<std::uint32_t, Swap>(src, dst, n);
  }
  throw std::invalid_argument("unknown ENVI data type " + std::to_string(static_cast<int>(type)));
}

template <bool Swap>
void encodeWith(EnviDataType type, const float* src, std::byte* dst, std::size_t n) {
  switch (type) {
    case EnviDataType::uint8: return encodeAs<std::uint8_t, Swap>(src, dst, n);
    case EnviDataType::int16: return encodeAs<std::int16_t, Swap>(src, dst, n);
    case EnviDataType::int32: return encodeAs<std::int32_t, Swap>(src, dst, n);
    case EnviDataType::float32: return encodeAs<float, Swap>(src, dst, n);
    case EnviDataType::float64: return encodeAs<double, Swap>(src, dst, n);
    case EnviDataType::uint16: return encodeAs<std::uint16_t, Swap>(src, dst, n);
    case EnviDataType::uint32: return encodeAs<std::uint32_t, Swap>(src, dst, n);
  }
  throw std::invalid_argument("unknown ENVI data type " + std::to_string(static_cast<int>(type)));
}

template <typename T, bool Swap>
inline float decodeOne(const std::byte* src) {
  Bits<T> bits;
  std::memcpy(&bits, src, sizeof(T));
  if constexpr (Swap) bits = swapBits(bits);
  return static_cast<float>(std::bit_cast<T>(bits));
}

// Output rows written per pass (see float_transpose.cc for the measurement).
constexpr std::size_t kBandBlock = 16;

// The fused path for 16-bit values: each 4 x 4 block is four 8-byte loads,
// widened to 32-bit integers, converted and transposed in registers.
template <typename T, bool Swap>
void decodeTransposed16(const std::byte* src, std::size_t pixels, std::size_t bands, float* out,
                        std::size_t out_stride) {
  static_assert(sizeof(T) == 2);
  const std::size_t pixel_bytes = bands * 2;
  for (std::size_t b0 = 0; b0 < bands; b0 += kBandBlock) {
    const std::size_t b1 = std::min(bands, b0 + kBandBlock);
    std::size_t p = 0;
#if defined(__SSE2__)
    const auto widen = [](__m128i x) {
      if constexpr (Swap) x = _mm_or_si128(_mm_slli_epi16(x, 8), _mm_srli_epi16(x, 8));
      if constexpr (std::is_signed_v<T>) {
        return _mm_cvtepi32_ps(_mm_srai_epi32(_mm_unpacklo_epi16(x, x), 16));  // sign-extend
      } else {
        return _mm_cvtepi32_ps(_mm_unpacklo_epi16(x, _mm_setzero_si128()));
      }
    };
    for (; p + 4 <= pixels; p += 4) {
      const std::byte* r0 = src + p * pixel_bytes;
      const std::byte* r1 = r0 + pixel_bytes;
      const std::byte* r2 = r1 + pixel_bytes;
      const std::byte* r3 = r2 + pixel_bytes;
      std::size_t b = b0;
      for (; b + 4 <= b1; b += 4) {
        __m128 a0 = widen(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r0 + 2 * b)));
        __m128 a1 = widen(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r1 + 2 * b)));
        __m128 a2 = widen(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r2 + 2 * b)));
        __m128 a3 = widen(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r3 + 2 * b)));
        _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
        _mm_storeu_ps(out + (b + 0) * out_stride + p, a0);
        _mm_storeu_ps(out + (b + 1) * out_stride + p, a1);
        _mm_storeu_ps(out + (b + 2) * out_stride + p, a2);
        _mm_storeu_ps(out + (b + 3) * out_stride + p, a3);
      }
      for (; b < b1; ++b) {
        float* row = out + b * out_stride + p;
        row[0] = decodeOne<T, Swap>(r0 + 2 * b);
        row[1] = decodeOne<T, Swap>(r1 + 2 * b);
        row[2] = decodeOne<T, Swap>(r2 + 2 * b);
        row[3] = decodeOne<T, Swap>(r3 + 2 * b);
      }
    }
#endif
    for (; p < pixels; ++p) {
      for (std::size_t b = b0; b < b1; ++b) out[b * out_stride + p] = decodeOne<T, Swap>(src + p * pixel_bytes + 2 * b);
    }
  }
}

// Any type: convert tiles of whole pixels (about 128 KB of floats; 64 to 256
// pixels of 211 bands measured equally fast), then transpose each tile.
void decodeTransposedByTiles(EnviDataType type, bool swap_bytes, const std::byte* src, std::size_t pixels,
                             std::size_t bands, float* out, std::size_t out_stride) {
  constexpr std::size_t kTileValues = 32768;
  const std::size_t value_bytes = bytesPerValue(type);
  const std::size_t tile_pixels = std::max<std::size_t>(1, kTileValues / bands);
  thread_local std::vector<float> tile;  // per thread: readers may run in parallel
  tile.resize(tile_pixels * bands);
  for (std::size_t p0 = 0; p0 < pixels; p0 += tile_pixels) {
    const std::size_t count = std::min(tile_pixels, pixels - p0);
    decodeSamples(type, swap_bytes, src + p0 * bands * value_bytes, tile.data(), count * bands);
    transposeFloats(tile.data(), count, bands, bands, out + p0, out_stride);
  }
}

}  // namespace

void decodeSamplesTransposed(EnviDataType type, bool swap_bytes, const std::byte* src, std::size_t pixels,
                             std::size_t bands, float* out, std::size_t out_stride) {
  if (type == EnviDataType::uint16) {
    return swap_bytes ? decodeTransposed16<std::uint16_t, true>(src, pixels, bands, out, out_stride)
                      : decodeTransposed16<std::uint16_t, false>(src, pixels, bands, out, out_stride);
  }
  if (type == EnviDataType::int16) {
    return swap_bytes ? decodeTransposed16<std::int16_t, true>(src, pixels, bands, out, out_stride)
                      : decodeTransposed16<std::int16_t, false>(src, pixels, bands, out, out_stride);
  }
  decodeTransposedByTiles(type, swap_bytes, src, pixels, bands, out, out_stride);
}

bool enviNeedsByteSwap(int byte_order) {
  const bool file_big_endian = byte_order == 1;
  return file_big_endian != (std::endian::native == std::endian::big);
}

void decodeSamples(EnviDataType type, bool swap_bytes, const std::byte* src, float* dst, std::size_t n) {
  if (swap_bytes) {
    decodeWith<true>(type, src, dst, n);
  } else {
    decodeWith<false>(type, src, dst, n);
  }
}

void encodeSamples(EnviDataType type, bool swap_bytes, const float* src, std::byte* dst, std::size_t n) {
  if (swap_bytes) {
    encodeWith<true>(type, src, dst, n);
  } else {
    encodeWith<false>(type, src, dst, n);
  }
}

}  // namespace hsmap
