#include "core/io/image_integrity.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::readText;
using testing::TempFolder;
using testing::writeText;

// A textured image, so that its compressed data is not trivially short.
cv::Mat texturedImage() {
  cv::Mat image(120, 160, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(image, cv::RNG::UNIFORM, 0, 255);
  return image;
}

struct Files {
  TempFolder dir{"image-integrity"};
  std::string png, jpeg;
  Files() {
    EXPECT_TRUE(cv::imwrite((dir / "a.png").string(), texturedImage()));
    EXPECT_TRUE(cv::imwrite((dir / "a.jpg").string(), texturedImage()));
    png = readText(dir / "a.png");
    jpeg = readText(dir / "a.jpg");
  }
};

TEST(ImageIntegrity, WholePngAndJpegFilesHaveNoDamage) {
  const Files files;
  EXPECT_EQ(findImageDamage(files.dir / "a.png"), std::nullopt);
  EXPECT_EQ(findImageDamage(files.dir / "a.jpg"), std::nullopt);
  // Zero padding after a JPEG's end-of-image marker is allowed.
  writeText(files.dir / "padded.jpg", files.jpeg + std::string(16, '\0'));
  EXPECT_EQ(findImageDamage(files.dir / "padded.jpg"), std::nullopt);
}

TEST(ImageIntegrity, ATruncatedPngIsFoundWhereverItIsCut) {
  const Files files;
  // Cut inside the image data, inside a chunk header, and just before IEND.
  for (std::size_t keep : {files.png.size() / 2, std::size_t(35), files.png.size() - 12}) {
    SCOPED_TRACE("kept " + std::to_string(keep) + " bytes");
    writeText(files.dir / "cut.png", files.png.substr(0, keep));
    const auto damage = findImageDamage(files.dir / "cut.png");
    ASSERT_TRUE(damage);
    EXPECT_EQ(damage->rfind("truncated: the file ends at byte " + std::to_string(keep), 0), 0u) << *damage;
  }
  writeText(files.dir / "cut.png", files.png.substr(0, files.png.size() - 12));
  EXPECT_EQ(*findImageDamage(files.dir / "cut.png"),
            "truncated: the file ends at byte " + std::to_string(files.png.size() - 12) + " before the IEND chunk");
}

TEST(ImageIntegrity, AChangedByteInAPngFailsItsChunksCrc) {
  const Files files;
  std::string changed = files.png;
  // A byte in the middle of the file: inside IDAT for this image.
  const std::size_t at = changed.size() / 2;
  changed[at] = char(changed[at] ^ 0x5A);
  writeText(files.dir / "changed.png", changed);
  const auto damage = findImageDamage(files.dir / "changed.png");
  ASSERT_TRUE(damage);
  EXPECT_NE(damage->find("the IDAT chunk at byte "), std::string::npos) << *damage;
  EXPECT_NE(damage->find("fails its CRC"), std::string::npos) << *damage;
}

TEST(ImageIntegrity, ATruncatedJpegHasNoEndOfImageMarker) {
  const Files files;
  const std::size_t keep = files.jpeg.size() - 100;
  writeText(files.dir / "cut.jpg", files.jpeg.substr(0, keep));
  EXPECT_EQ(*findImageDamage(files.dir / "cut.jpg"),
            "truncated: no end-of-image marker (FF D9) at the end of the file (" + std::to_string(keep) + " bytes)");
}

TEST(ImageIntegrity, EmptyForeignAndMissingFiles) {
  const Files files;
  writeText(files.dir / "empty.png", "");
  EXPECT_EQ(*findImageDamage(files.dir / "empty.png"), "an empty file");
  writeText(files.dir / "script.png", "#!/bin/sh\necho hi\n");
  EXPECT_EQ(*findImageDamage(files.dir / "script.png"), "not a PNG or JPEG image");
  EXPECT_THROW(findImageDamage(files.dir / "missing.png"), InputError);
}

}  // namespace
}  // namespace hsmap
