#include "core/survey/rgb_frame_source.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

cv::Mat patternImage(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

class RgbFrameSourceTest : public ::testing::Test {
 protected:
  TempFolder folder_{"rgb"};

  // Writes n PNG frames and frames.csv (t = 10 + 0.04 i) into rgb/.
  std::filesystem::path writeFrameList(int n) {
    std::vector<FrameRow> rows;
    for (int i = 0; i < n; ++i) {
      char name[32];
      std::snprintf(name, sizeof(name), "f%d.png", i);
      EXPECT_TRUE(cv::imwrite((folder_ / "rgb" / name).string(), patternImage(32, 24, i)));
      rows.push_back({name, 10.0 + 0.04 * i, 0});
    }
    writeFramesCsv(folder_ / "rgb" / "frames.csv", rows);
    return folder_ / "rgb" / "frames.csv";
  }

  void SetUp() override { std::filesystem::create_directories(folder_ / "rgb"); }
};

TEST_F(RgbFrameSourceTest, FrameListGivesTimesPathsAndImages) {
  const auto csv = writeFrameList(3);
  const RgbFrameSource source = RgbFrameSource::fromFrameList(csv);
  EXPECT_FALSE(source.isVideo());
  EXPECT_EQ(source.sourcePath(), csv);
  ASSERT_EQ(source.frameCount(), 3);
  EXPECT_EQ(source.time(2), 10.0 + 0.04 * 2);
  EXPECT_EQ(source.framePath(1), folder_ / "rgb" / "f1.png");
  const cv::Mat image = source.frame(1);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(image, patternImage(32, 24, 1), cv::NORM_INF), 0.0);  // PNG is lossless
  EXPECT_EQ(source.frameSize(), cv::Size(32, 24));
  EXPECT_THROW(source.frame(3), std::out_of_range);
}

TEST_F(RgbFrameSourceTest, MissingImageIsReportedAtItsCsvLine) {
  const auto csv = writeFrameList(4);
  std::filesystem::remove(folder_ / "rgb" / "f2.png");
  try {
    RgbFrameSource::fromFrameList(csv);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), csv.string() +
                                         ":line 4: column 'file': image 'f2.png' not found "
                                         "(expected the file " +
                                         (folder_ / "rgb" / "f2.png").string() + ")");
  }
}

TEST_F(RgbFrameSourceTest, ForeignFileIsReportedAtItsCsvLineWithoutDecoding) {
  const auto csv = writeFrameList(3);
  testing::writeText(folder_ / "rgb" / "f1.png", "this is not a PNG");
  try {
    RgbFrameSource::fromFrameList(csv);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              csv.string() + ":line 3: column 'file': image 'f1.png' is not a PNG or JPEG image "
                             "(it starts with 'this is ') (" +
                  (folder_ / "rgb" / "f1.png").string() + ")");
  }
}

TEST_F(RgbFrameSourceTest, UndecodableImageNamesTheImageAndItsCsvLineInOneLine) {
  const auto csv = writeFrameList(2);
  // A valid PNG header (signature and IHDR) followed by damaged image data:
  // it passes the header check and fails only when decoded.
  const auto image = folder_ / "rgb" / "f1.png";
  std::string png = testing::readText(image);
  for (std::size_t i = 40; i < png.size(); ++i) png[i] = static_cast<char>(png[i] ^ 0x5A);
  testing::writeText(image, png);
  const RgbFrameSource source = RgbFrameSource::fromFrameList(csv);
  ::testing::internal::CaptureStderr();
  try {
    source.frame(1);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), image);
    const std::string prefix =
        image.string() + ": cannot decode the image (listed at " + csv.string() + ":line 3)";
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // What libpng printed went into the message, not onto the terminal.
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST_F(RgbFrameSourceTest, VideoGivesFrameCountTimesAndFramesInAnyOrder) {
  const auto video = folder_ / "rgb" / "dive.avi";
  {
    // OpenCV's built-in MJPEG writer needs no external codec.
    cv::VideoWriter writer(video.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0,
                           cv::Size(64, 48));
    ASSERT_TRUE(writer.isOpened());
    for (int i = 0; i < 8; ++i) {
      cv::Mat frame(48, 64, CV_8UC3, cv::Scalar(20 * i, 100, 255 - 20 * i));
      writer.write(frame);
    }
  }
  const RgbFrameSource source = RgbFrameSource::fromVideo(video, 100.0, 10.0);
  EXPECT_TRUE(source.isVideo());
  ASSERT_EQ(source.frameCount(), 8);
  EXPECT_EQ(source.time(0), 100.0);
  EXPECT_DOUBLE_EQ(source.time(5), 100.5);
  EXPECT_EQ(source.frameSize(), cv::Size(64, 48));
  for (int i : {0, 1, 5, 2, 7}) {
    const cv::Mat frame = source.frame(i);
    ASSERT_EQ(frame.size(), cv::Size(64, 48));
    // JPEG is lossy but a flat colour survives within a few levels.
    EXPECT_NEAR(cv::mean(frame)[0], 20.0 * i, 4.0) << "frame " << i;
  }
}

TEST_F(RgbFrameSourceTest, MissingOrUnreadableVideo) {
  const auto absent = folder_ / "rgb" / "absent.mp4";
  try {
    RgbFrameSource::fromVideo(absent, 0.0, 25.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), absent.string() + ": video file not found");
  }
  const auto garbage = folder_ / "rgb" / "garbage.mp4";
  testing::writeText(garbage, "not a video at all");
  try {
    RgbFrameSource::fromVideo(garbage, 0.0, 25.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), garbage);
    EXPECT_EQ(std::string(e.what()).rfind(
                  garbage.string() + ": cannot open the video (unsupported container or codec?)", 0),
              0u)
        << e.what();
  }
}

}  // namespace
}  // namespace hsmap
