#pragma once
// transposeFloats: dst(c, r) = src(r, c) for a rows x cols block of floats,
// each matrix row-major with its own stride (in floats):
//   dst[c * dst_stride + r] = src[r * src_stride + c].
// Used to turn BIP pixels (pixel-major) into band-major lines and back.
// Works in passes of 16 source columns (so that only 16 destination rows are
// written at a time), each in 4 x 4 blocks with SSE shuffles where available
// (an element-by-element transpose costs more than reading the cube), and
// element by element for the edges and on other targets.

#include <cstddef>

namespace hsmap {

void transposeFloats(const float* src, std::size_t rows, std::size_t cols, std::size_t src_stride, float* dst,
                     std::size_t dst_stride);

// The same with source row r multiplied by row_scale[r] (rows values):
//   dst[c * dst_stride + r] = src[r * src_stride + c] * row_scale[r],
// bit for bit what scaling the rows first and transposing after gives.
// For sums turned into means as they are transposed (one pass, not two).
void transposeScaledRows(const float* src, std::size_t rows, std::size_t cols, std::size_t src_stride,
                         const float* row_scale, float* dst, std::size_t dst_stride);

}  // namespace hsmap
