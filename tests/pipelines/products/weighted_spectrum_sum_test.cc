// weightedSpectrumSum gives, bit for bit, the plain loop over sources and
// bands that defines it, for band counts around its blocks and any number of
// sources (including none).
#include "pipelines/products/weighted_spectrum_sum.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hsmap {
namespace {

TEST(WeightedSpectrumSum, EqualsTheLoopThatDefinesItBitForBit) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-3.0e3f, 9.0e3f), weight(0.02f, 1.0f), scale(0.01f, 1.0f);
  for (int bands : {1, 7, 31, 32, 33, 64, 211}) {
    for (int count : {0, 1, 2, 5, 17}) {
      std::vector<std::vector<float>> spectra(std::size_t(count), std::vector<float>(std::size_t(bands), 0.0f));
      std::vector<const float*> sources;
      std::vector<float> weights, scales;
      for (auto& spectrum : spectra) {
        for (float& v : spectrum) v = value(random);
        sources.push_back(spectrum.data());
        weights.push_back(weight(random));
        scales.push_back(1.0f / float(1 + random() % 9) * scale(random));
      }
      std::vector<float> expected(std::size_t(bands), 0.0f);
      for (std::size_t k = 0; k < std::size_t(count); ++k) {
        for (std::size_t b = 0; b < std::size_t(bands); ++b) {
          expected[b] += weights[k] * (spectra[k][b] * scales[k]);
        }
      }
      std::vector<float> out(std::size_t(bands), -1.0f);
      weightedSpectrumSum(sources.data(), weights.data(), scales.data(), count, bands, out.data());
      for (int b = 0; b < bands; ++b) {
        ASSERT_EQ(out[std::size_t(b)], expected[std::size_t(b)])
            << bands << " bands, " << count << " sources, band " << b;
      }
    }
  }
}

}  // namespace
}  // namespace hsmap
