#include "pipelines/frontend/tracking_loss_monitor.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

TEST(TrackingLossMonitor, NamesBlackFlatAndOverExposedFrames) {
  const FrontendOptions options;
  const auto black = textureProblem(ImagePreprocessor::measure(cv::Mat::zeros(90, 160, CV_8U)), options);
  ASSERT_TRUE(black);
  EXPECT_NE(black->find("dark"), std::string::npos);
  const auto flat = textureProblem(ImagePreprocessor::measure(cv::Mat(90, 160, CV_8U, cv::Scalar(128))), options);
  ASSERT_TRUE(flat);
  EXPECT_NE(flat->find("flat"), std::string::npos);
  const auto white = textureProblem(ImagePreprocessor::measure(cv::Mat(90, 160, CV_8U, cv::Scalar(255))), options);
  ASSERT_TRUE(white);
  EXPECT_NE(white->find("over-exposed"), std::string::npos);
  cv::Mat textured(90, 160, CV_8U);
  cv::RNG(3).fill(textured, cv::RNG::UNIFORM, 30, 220);
  EXPECT_FALSE(textureProblem(ImagePreprocessor::measure(textured), options));
}

TEST(TrackingLossMonitor, EveryRunOfUnposedFramesIsOneLossWithItsFirstReason) {
  std::vector<FrameRecord> frames(12);
  for (int i = 0; i < 12; ++i) {
    frames[std::size_t(i)].index = 100 + i;
    frames[std::size_t(i)].posed = !(i >= 3 && i <= 6) && i != 9 && i != 11;
  }
  const std::map<int, std::string> reasons{{104, "second"}, {103, "first"}, {111, "last"}};
  const auto losses = collectLosses(frames, reasons);
  ASSERT_EQ(losses.size(), 3u);
  EXPECT_EQ(losses[0].first_frame, 103);
  EXPECT_EQ(losses[0].last_frame, 106);
  EXPECT_EQ(losses[0].reason, "first");
  EXPECT_EQ(losses[1].first_frame, 109);
  EXPECT_EQ(losses[1].last_frame, 109);
  EXPECT_EQ(losses[1].reason, "not posed");
  EXPECT_EQ(losses[2].first_frame, 111);
  EXPECT_EQ(losses[2].last_frame, 111);
  EXPECT_EQ(losses[2].reason, "last");
}

}  // namespace
}  // namespace hsmap
