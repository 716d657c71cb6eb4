#include "core/util/message_text.h"

#include <gtest/gtest.h>

namespace hsmap {
namespace {

TEST(MessageTextTest, ShortPrintableTextIsUnchanged) {
  EXPECT_EQ(escapeForMessage("12abc"), "12abc");
  EXPECT_EQ(quoteForMessage("nan"), "'nan'");
  EXPECT_EQ(escapeForMessage("température 20 °C"), "température 20 °C");
}

TEST(MessageTextTest, ControlCharactersAndInvalidBytesAreEscaped) {
  EXPECT_EQ(escapeForMessage(std::string("a\nb\rc\td\\e\0f", 11)), "a\\nb\\rc\\td\\\\e\\x00f");
  EXPECT_EQ(escapeForMessage("x\xFF\xC3y"), "x\\xFF\\xC3y");  // stray byte, truncated sequence
  EXPECT_EQ(escapeForMessage("\xC0\xAF"), "\\xC0\\xAF");      // overlong '/'
  EXPECT_EQ(escapeForMessage("\xED\xA0\x80"), "\\xED\\xA0\\x80");  // UTF-16 surrogate
  EXPECT_EQ(escapeForMessage("\x7F"), "\\x7F");
}

TEST(MessageTextTest, LongTextIsCutWithItsSize) {
  const std::string long_text(100000, 'z');
  EXPECT_EQ(escapeForMessage(long_text, 10), "zzzzzzzzzz... (100000 bytes)");
  // An escape counts as its printed width: no escape is cut in half.
  EXPECT_EQ(escapeForMessage("abcdefghi\n", 10), "abcdefghi... (10 bytes)");
  // A multi-byte character counts as one column and is never split.
  EXPECT_EQ(escapeForMessage("°°°°", 3), "°°°... (8 bytes)");
}

TEST(MessageTextTest, Utf8SequenceLengths) {
  EXPECT_EQ(utf8SequenceLength("a"), 1u);
  EXPECT_EQ(utf8SequenceLength("\xC2\xB0"), 2u);
  EXPECT_EQ(utf8SequenceLength("\xE2\x82\xAC"), 3u);
  EXPECT_EQ(utf8SequenceLength("\xF0\x9F\x90\x9F"), 4u);
  EXPECT_EQ(utf8SequenceLength("\xF4\x90\x80\x80"), 0u);  // above U+10FFFF
  EXPECT_EQ(utf8SequenceLength("\x80"), 0u);
  EXPECT_EQ(utf8SequenceLength("\xE2\x82"), 0u);
  EXPECT_EQ(utf8SequenceLength(""), 0u);
}

TEST(MessageTextTest, FixedDecimalsPrintsExactlyTheDigitsAskedFor) {
  EXPECT_EQ(fixedDecimals(0.125, 3), "0.125");
  EXPECT_EQ(fixedDecimals(3.0, 1), "3.0");
  EXPECT_EQ(fixedDecimals(-2.46, 1), "-2.5");
  EXPECT_EQ(fixedDecimals(36000.5156, 3), "36000.516");
  EXPECT_EQ(fixedDecimals(7.6, 0), "8");
  // Beyond the 64 characters a fixed buffer would have held.
  EXPECT_EQ(fixedDecimals(1e70, 2).size(), 71u + 3u);
}

}  // namespace
}  // namespace hsmap
