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

// Decodes a pixel-major block (BIP: `pixels` runs of `bands` values) into
// band-major rows: out[b * out_stride + p] = value of src[p * bands + b].
// 16-bit types (the usual UHI data) convert and transpose in one pass over
// 4 x 4 blocks with SSE2; other types convert a tile of pixels and then
// transpose it (transposeFloats). Either way, only 16 output rows are written
// at a time, so that the stores stay in few streams.
void decodeSamplesTransposed(EnviDataType type, bool swap_bytes, const std::byte* src, std::size_t pixels,
                             std::size_t bands, float* out, std::size_t out_stride);
void encodeSamples(EnviDataType type, bool swap_bytes, const float* src, std::byte* dst, std::size_t n);

}  // namespace hsmap
