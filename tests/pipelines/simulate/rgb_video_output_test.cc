// rgb.encoding: the simulated frames written as JPEG files or as one H.264
// video load through the survey loader with the frame count and times of the
// lossless PNG frames, and decode close to them.
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "core/survey/survey.h"
#include "pipelines/simulate/simulate_survey.h"
#include "tests/pipelines/simulate/tiny_survey.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

// The PSNR (dB) of every frame of `survey` against tiny's lossless frames;
// returns the lowest.
double lowestPsnr(const Survey& survey) {
  const Survey lossless = loadSurvey(testing::tinySurvey().folder);
  double lowest = 1e300;
  for (int k = 0; k < survey.rgb.frameCount(); ++k) {
    lowest = std::min(lowest, cv::PSNR(survey.rgb.frame(k), lossless.rgb.frame(k)));
  }
  return lowest;
}

void expectTinysFramesAndTimes(const Survey& survey) {
  const Survey lossless = loadSurvey(testing::tinySurvey().folder);
  ASSERT_EQ(survey.rgb.frameCount(), lossless.rgb.frameCount());
  for (int k = 0; k < survey.rgb.frameCount(); ++k) {
    EXPECT_NEAR(survey.rgb.time(k), lossless.rgb.time(k), 1e-9) << "frame " << k;
  }
  EXPECT_EQ(survey.rgb.frameSize(), lossless.rgb.frameSize());
}

TEST(RgbVideoOutput, H264VideoLoadsWithTheFramesTimesAndCloseToTheLosslessFrames) {
  SimulationConfig config = testing::tinySurvey().config;
  config.rgb.encoding.format = RgbFrameFormat::h264;
  testing::TempFolder temp("h264");
  std::ostringstream log;
  const SimulationSummary summary = simulateSurvey(config, temp / "survey", log);
  EXPECT_FALSE(std::filesystem::exists(temp / "survey" / "rgb" / "frames.csv"));
  EXPECT_FALSE(std::filesystem::exists(temp / "survey" / "rgb" / "frame_000000.png"));
  ASSERT_TRUE(std::filesystem::exists(temp / "survey" / "rgb" / "video.mp4"));
  EXPECT_EQ(summary.rgb_bytes, std::filesystem::file_size(temp / "survey" / "rgb" / "video.mp4"));

  const Survey survey = loadSurvey(temp / "survey");
  ASSERT_TRUE(survey.rgb.isVideo());
  ASSERT_TRUE(survey.config.rgb.video.has_value());
  EXPECT_EQ(survey.config.rgb.video->fps, config.rgb.rate_hz);
  expectTinysFramesAndTimes(survey);
  const double psnr = lowestPsnr(survey);
  // libx264 at CRF 23 (all OpenCV lets us set) on tiny's noisy 320x180
  // frames: 0.37 Mbit/s, 29.7 dB for the worst frame.
  EXPECT_GT(psnr, 28.0);
}

TEST(RgbVideoOutput, JpegFramesLoadWithTheFramesTimesAndCloseToTheLosslessFrames) {
  SimulationConfig config = testing::tinySurvey().config;
  config.rgb.encoding.format = RgbFrameFormat::jpeg;
  config.rgb.encoding.jpeg_quality = 90;
  testing::TempFolder temp("jpeg");
  std::ostringstream log;
  const SimulationSummary summary = simulateSurvey(config, temp / "survey", log);
  ASSERT_TRUE(std::filesystem::exists(temp / "survey" / "rgb" / "frame_000000.jpg"));
  const Survey survey = loadSurvey(temp / "survey");
  EXPECT_FALSE(survey.rgb.isVideo());
  expectTinysFramesAndTimes(survey);
  const double psnr = lowestPsnr(survey);
  // Quality 90: about 23 kB a frame, 32.5 dB for the worst frame.
  EXPECT_GT(psnr, 31.0);
  EXPECT_LT(summary.rgb_bytes, 58u * 40000u);
}

}  // namespace
}  // namespace hsmap
