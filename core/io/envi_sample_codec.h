#pragma once
// Conversion between the values of an ENVI data file (any data type, either
// byte order) and float32, the type every hsmap computation reads.
//
// decodeSamples: n stored values -> n floats. Integers convert exactly up to
// 2^24 (all of uint8/int16/uint16); int32/uint32/float64 round to the
// nearest float.
// encodeSamples: n floats -> n stored values. Integer types round to the
// nearest integer (halves away from zero) and clamp to the type's range; NaN
// becomes 0 (integer ENVI files have no NaN; a `data ignore value` is the
// caller's business). Float types convert directly.
//
// Both work on unaligned byte buffers (a header offset need not be a multiple
// of the value size) and are written as tight loops over memcpy'd values so
// that the compiler vectorises them; the byte swap is a separate
// instantiation, used only when the file's byte order differs from the host's.

#include <cstddef>

#include "core/io/envi_header.h"

namespace hsmap {

// True when values stored with ENVI `byte order` (0 little, 1 big endian)
// must be byte-swapped on this machine.
bool enviNeedsByteSwap(int byte_order);

void decodeSamples(EnviDataType type, bool swap_bytes, const std::byte* src, float* dst, std::size_t n);
void encodeSamples(EnviDataType type, bool swap_bytes, const float* src, std::byte* dst, std::size_t n);

}  // namespace hsmap
