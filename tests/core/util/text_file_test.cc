#include "core/util/text_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "core/util/input_error.h"
#include "core/util/regular_file.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

TEST(TextFileTest, LineEndsAreNormalisedAndByteOrderMarkDropped) {
  EXPECT_EQ(normaliseText("a\r\nb\rc\nd", "f", TextEncoding::utf8), "a\nb\nc\nd");
  EXPECT_EQ(normaliseText("\xEF\xBB\xBFkey: 1\r\r", "f", TextEncoding::utf8), "key: 1\n\n");
  EXPECT_EQ(normaliseText("tab\there", "f", TextEncoding::utf8), "tab\there");
}

TEST(TextFileTest, ControlCharactersAreErrorsAtTheirLineAndColumn) {
  expectInputError([] { normaliseText(std::string("ok\nab\0c", 7), "t.csv", TextEncoding::utf8); },
                   "t.csv", "line 2: control character 0x00 (NUL) in column 3; expected text (is "
                            "this a binary or damaged file?)");
  expectInputError([] { normaliseText("a\r\n\x1B[0m", "t.csv", TextEncoding::any_bytes); },
                   "t.csv", "line 2: control character 0x1B in column 1; expected text (is this "
                            "a binary or damaged file?)");
}

TEST(TextFileTest, NonUtf8IsAnErrorUnlessAnyBytesAreAllowed) {
  expectInputError([] { normaliseText("name: caf\xE9\n", "s.yaml", TextEncoding::utf8); },
                   "s.yaml", "line 1: byte 0xE9 in column 10 is not UTF-8; expected UTF-8 text");
  EXPECT_EQ(normaliseText("d = caf\xE9", "h.hdr", TextEncoding::any_bytes), "d = caf\xE9");
  EXPECT_EQ(normaliseText("caf\xC3\xA9", "s.yaml", TextEncoding::utf8), "caf\xC3\xA9");
}

TEST(TextFileTest, ReadsRegularFilesWithinTheLimitOnly) {
  const TempFolder dir("text-file");
  writeText(dir / "small.txt", "hello");
  EXPECT_EQ(readTextFile(dir / "small.txt", 5), "hello");
  expectInputError([&] { readTextFile(dir / "small.txt", 4); }, dir / "small.txt",
                   " the file is 5 bytes; expected a text file of at most 4 bytes");
  expectInputError([&] { readTextFile(dir / "absent.txt", 10); }, dir / "absent.txt",
                   " file not found");
  expectInputError([&] { readTextFile(dir.path(), 10); }, dir.path(),
                   " is a directory; expected a regular file");
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  // Would block forever in open() without O_NONBLOCK.
  expectInputError([&] { readTextFile(dir / "pipe", 10); }, dir / "pipe",
                   " is a named pipe (FIFO); expected a regular file");
  expectInputError([&] { readTextFile("/dev/zero", 10); }, "/dev/zero",
                   " is a character device; expected a regular file");
}

TEST(RegularFileTest, WhyNotRegularNamesTheKindOfFile) {
  const TempFolder dir("regular-file");
  writeText(dir / "a.txt", "x");
  EXPECT_FALSE(whyNotRegularFile(dir / "a.txt").has_value());
  EXPECT_EQ(whyNotRegularFile(dir / "none").value(), "not found");
  EXPECT_EQ(whyNotRegularFile(dir / "a.txt" / "below").value(), "not found");
  EXPECT_EQ(whyNotRegularFile(dir.path()).value(), "a directory");
  EXPECT_EQ(whyNotRegularFile("/dev/null").value(), "a character device");
  const RegularFile file(dir / "a.txt");
  EXPECT_EQ(file.size(), 1u);
  EXPECT_GE(file.fd(), 0);
}

}  // namespace
}  // namespace hsmap
