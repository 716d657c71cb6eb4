#include "pipelines/products/weighted_spectrum_sum.h"

#include <cstring>

namespace hsmap {

namespace {

// Eight floats as one value (GCC's vector extension): one AVX2 register, or
// two SSE registers on the baseline; element-wise IEEE operations either way.
using Floats8 = float __attribute__((vector_size(32)));

// out += weight * (p[0..8) * scale), element by element. By reference, not
// by value: a function passing a 32-byte vector by value would change its
// calling convention between the AVX2 and baseline builds.
inline void addWeighted(Floats8& out, const float* p, float weight, float scale) {
  Floats8 v;
  std::memcpy(&v, p, sizeof v);
  out += weight * (v * scale);
}

inline void store8(float* p, const Floats8& v) { std::memcpy(p, &v, sizeof v); }

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void weightedSpectrumSum(const float* const* sources, const float* weights, const float* scales, int count,
                         int bands, float* out) {
  int b = 0;
  // 32 bands at a time, their sums held in registers across the sources.
  for (; b + 32 <= bands; b += 32) {
    Floats8 s0 = {}, s1 = {}, s2 = {}, s3 = {};
    for (int k = 0; k < count; ++k) {
      const float* source = sources[k] + b;
      const float weight = weights[k], scale = scales[k];
      addWeighted(s0, source, weight, scale);
      addWeighted(s1, source + 8, weight, scale);
      addWeighted(s2, source + 16, weight, scale);
      addWeighted(s3, source + 24, weight, scale);
    }
    store8(out + b, s0);
    store8(out + b + 8, s1);
    store8(out + b + 16, s2);
    store8(out + b + 24, s3);
  }
  for (; b + 8 <= bands; b += 8) {
    Floats8 s = {};
    for (int k = 0; k < count; ++k) addWeighted(s, sources[k] + b, weights[k], scales[k]);
    store8(out + b, s);
  }
  for (; b < bands; ++b) {
    float s = 0.0f;
    for (int k = 0; k < count; ++k) s += weights[k] * (sources[k][b] * scales[k]);
    out[b] = s;
  }
}

}  // namespace hsmap
