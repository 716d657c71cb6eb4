#include "core/io/image_header.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::readText;
using testing::TempFolder;
using testing::writeText;

TEST(ImageHeaderTest, ReadsPngAndJpegSizesWithoutDecoding) {
  const TempFolder dir("image-header");
  const cv::Mat image(37, 53, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), image));
  ASSERT_TRUE(cv::imwrite((dir / "a.jpg").string(), image));
  std::string why;
  const auto png = readImageHeader(dir / "a.png", &why);
  ASSERT_TRUE(png) << why;
  EXPECT_EQ(png->format, "PNG");
  EXPECT_EQ(png->width, 53);
  EXPECT_EQ(png->height, 37);
  const auto jpeg = readImageHeader(dir / "a.jpg", &why);
  ASSERT_TRUE(jpeg) << why;
  EXPECT_EQ(jpeg->format, "JPEG");
  EXPECT_EQ(jpeg->width, 53);
  EXPECT_EQ(jpeg->height, 37);
}

TEST(ImageHeaderTest, SkipsLargeApplicationSegmentsBeforeTheFrameHeader) {
  const TempFolder dir("image-header-app");
  ASSERT_TRUE(cv::imwrite((dir / "a.jpg").string(), cv::Mat(20, 30, CV_8UC1, cv::Scalar(5))));
  std::string jpeg = readText(dir / "a.jpg");
  // An APP1 segment of 60,000 bytes (an EXIF thumbnail, say) right after SOI.
  std::string app1 = "\xFF\xE1";
  const int length = 60000;
  app1 += static_cast<char>(length >> 8);
  app1 += static_cast<char>(length & 0xFF);
  app1 += std::string(length - 2, '\xAB');
  jpeg.insert(2, app1);
  writeText(dir / "b.jpg", jpeg);
  std::string why;
  const auto header = readImageHeader(dir / "b.jpg", &why);
  ASSERT_TRUE(header) << why;
  EXPECT_EQ(header->width, 30);
  EXPECT_EQ(header->height, 20);
}

TEST(ImageHeaderTest, DamagedAndForeignFilesAreExplained) {
  const TempFolder dir("image-header-bad");
  const auto reason = [&](const std::string& content) {
    writeText(dir / "x", content);
    std::string why;
    EXPECT_FALSE(readImageHeader(dir / "x", &why));
    return why;
  };
  EXPECT_EQ(reason(""), "an empty file");
  EXPECT_EQ(reason("root:x:0:0:root"), "not a PNG or JPEG image (it starts with 'root:x:0')");
  EXPECT_EQ(reason("\x89PNG\r\n\x1A\n"), "a damaged PNG image (no IHDR chunk after the signature)");
  EXPECT_EQ(reason(std::string("\x89PNG\r\n\x1A\n\0\0\0\x0DIHDR\0\0\0\0\0\0\0\x05", 24)),
            "a damaged PNG image (IHDR gives 0x5 pixels)");
  EXPECT_EQ(reason("\xFF\xD8\xFF\xE0\x00\x10JFIF"),
            "a damaged JPEG image (no frame header before the image data ends)");
  EXPECT_EQ(reason("\xFF\xD8\xFF\xD9"),
            "a damaged JPEG image (no frame header before the image data ends)");
}

}  // namespace
}  // namespace hsmap
