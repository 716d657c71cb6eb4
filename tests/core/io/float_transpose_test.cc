#include "core/io/float_transpose.h"

#include <vector>

#include <gtest/gtest.h>

namespace hsmap {
namespace {

// Every shape around the 4 x 4 blocks and the 16-column passes, with
// strides wider than the block.
TEST(FloatTranspose, MatchesTheDefinitionForEveryShape) {
  for (std::size_t rows : {1, 2, 3, 4, 5, 7, 8, 9, 23}) {
    for (std::size_t cols : {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 33, 211}) {
      const std::size_t src_stride = cols + 2, dst_stride = rows + 3;
      std::vector<float> src(rows * src_stride);
      for (std::size_t i = 0; i < src.size(); ++i) src[i] = static_cast<float>(i) + 0.5f;
      std::vector<float> dst(cols * dst_stride, -1.0f);
      transposeFloats(src.data(), rows, cols, src_stride, dst.data(), dst_stride);
      for (std::size_t c = 0; c < cols; ++c) {
        for (std::size_t r = 0; r < dst_stride; ++r) {
          const float expected = r < rows ? src[r * src_stride + c] : -1.0f;  // padding untouched
          ASSERT_EQ(dst[c * dst_stride + r], expected) << rows << "x" << cols << " at (" << c << ", " << r << ")";
        }
      }
    }
  }
}

// Each source row scaled on the way: the bits of scaling, then transposing.
TEST(FloatTranspose, ScaledRowsEqualScalingEachRowThenTransposing) {
  for (std::size_t rows : {1, 3, 4, 5, 9, 23}) {
    for (std::size_t cols : {1, 4, 7, 16, 17, 211}) {
      const std::size_t src_stride = cols + 1, dst_stride = rows + 2;
      std::vector<float> src(rows * src_stride), scale(rows);
      for (std::size_t i = 0; i < src.size(); ++i) src[i] = static_cast<float>(i) * 0.37f + 0.1f;
      for (std::size_t r = 0; r < rows; ++r) scale[r] = 1.0f / static_cast<float>(r + 3);
      std::vector<float> dst(cols * dst_stride, -1.0f);
      transposeScaledRows(src.data(), rows, cols, src_stride, scale.data(), dst.data(), dst_stride);
      for (std::size_t c = 0; c < cols; ++c) {
        for (std::size_t r = 0; r < dst_stride; ++r) {
          const float expected = r < rows ? src[r * src_stride + c] * scale[r] : -1.0f;
          ASSERT_EQ(dst[c * dst_stride + r], expected) << rows << "x" << cols << " at (" << c << ", " << r << ")";
        }
      }
    }
  }
}

}  // namespace
}  // namespace hsmap
