#include "core/util/stderr_capture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>

namespace hsmap {
namespace {

TEST(StderrCaptureTest, KeepsWhatIsWrittenToDescriptorTwoAndRestoresIt) {
  ::testing::internal::CaptureStderr();  // what reaches the real stderr
  {
    const StderrCapture capture;
    std::fputs("\nlibpng error: IHDR: CRC error\nsecond line\n", stderr);
    const char raw[] = "raw write\n";
    ASSERT_EQ(::write(STDERR_FILENO, raw, sizeof(raw) - 1), static_cast<ssize_t>(sizeof(raw) - 1));
    EXPECT_EQ(capture.firstLine(), "IHDR: CRC error");
    EXPECT_EQ(capture.text(), "\nlibpng error: IHDR: CRC error\nsecond line\nraw write\n");
  }
  std::fputs("after\n", stderr);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "after\n");
}

TEST(StderrCaptureTest, NothingWrittenGivesNoLine) {
  const StderrCapture capture;
  EXPECT_EQ(capture.firstLine(), "");
  EXPECT_EQ(capture.text(), "");
}

}  // namespace
}  // namespace hsmap
