#include "core/io/envi_sample_codec.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

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

}  // namespace

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
