// The `tiny` preset's RGB frames and their times are pinned to the values they had
// before the video effects (motion blur, vignetting, automatic gain, JPEG and
// H.264 output) were added, and its UHI cube to the bytes it had before the
// water effects (backscatter, marine snow): those effects are off in every
// preset, and off must mean the same pixels, not merely similar ones. The pixels are hashed
// after decoding, so a different PNG library (other compressed bytes of the
// same image) does not break the pin; the frame times as loaded. The files
// written by core/survey's writers (survey.yaml, the CSVs) are not pinned
// here: their format belongs to the survey format, not to the renderer.
//
// The pixel hash is of this platform's build (x86-64, Release); Embree and
// the compiler's floating point may round differently elsewhere.
//
// If a deliberate change to the renderer moves these values, update them in
// the same commit and say why in its message.
#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "core/survey/survey.h"
#include "tests/pipelines/simulate/tiny_survey.h"

namespace hsmap {
namespace {

// FNV-1a, 64 bits: a fixed recipe, the same on every platform.
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash = 0xcbf29ce484222325ull) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

TEST(PresetOutputPinned, TinyFramePixelsAndTimesAreThoseOfBeforeTheVideoEffects) {
  const auto& tiny = testing::tinySurvey();
  const Survey survey = loadSurvey(tiny.folder);
  ASSERT_EQ(survey.rgb.frameCount(), 58);
  std::uint64_t pixels = 0xcbf29ce484222325ull;
  for (int k = 0; k < survey.rgb.frameCount(); ++k) {
    const cv::Mat frame = survey.rgb.frame(k);
    ASSERT_TRUE(frame.isContinuous());
    pixels = fnv1a(frame.data, frame.total() * frame.elemSize(), pixels);
  }
  EXPECT_EQ(pixels, 12109789320167212237ull) << "decoded pixels of every frame";
  const std::vector<double>& times = survey.rgb.times();
  EXPECT_EQ(fnv1a(times.data(), times.size() * sizeof(double)), 10493557526601962291ull) << "frame times";
}

// The cube's raw bytes (uint16, BIL) as written: the UHI renderer's DN after
// rounding, with no image codec in between.
TEST(PresetOutputPinned, TinyUhiCubeBytesAreThoseOfBeforeTheWaterEffects) {
  const auto& tiny = testing::tinySurvey();
  std::ifstream raw(tiny.folder / "uhi" / "cube.raw", std::ios::binary);
  ASSERT_TRUE(raw.good());
  const std::vector<char> bytes((std::istreambuf_iterator<char>(raw)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.size(), std::size_t(tiny.summary.uhi_lines) * 240 * 24 * 2);
  EXPECT_EQ(fnv1a(bytes.data(), bytes.size()), 5594230518066452621ull) << "bytes of uhi/cube.raw";
}

}  // namespace
}  // namespace hsmap
