#include "core/survey/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace hsmap {
namespace {

TEST(NumberText, ParsesPlainNumbersWithBlanksAndPlus) {
  std::string message;
  EXPECT_EQ(parseFiniteDouble("1.5", &message), 1.5);
  EXPECT_EQ(parseFiniteDouble("  -2e3\t", &message), -2000.0);
  EXPECT_EQ(parseFiniteDouble("+0.25", &message), 0.25);
  EXPECT_EQ(parseInteger(" 42 ", &message), 42);
  EXPECT_EQ(parseInteger("-7", &message), -7);
}

TEST(NumberText, RejectsTextThatIsNotExactlyOneNumber) {
  for (const char* text : {"", "abc", "12abc", "1,5", "0x10", "--1", "+-1", "1 2"}) {
    std::string message;
    EXPECT_FALSE(parseFiniteDouble(text, &message).has_value()) << text;
    EXPECT_EQ(message, std::string("expected a number, got '") + text + "'");
  }
}

TEST(NumberText, RejectsNonFiniteNumbers) {
  for (const char* text : {"nan", "NaN", "inf", "-inf", "infinity"}) {
    std::string message;
    EXPECT_FALSE(parseFiniteDouble(text, &message).has_value()) << text;
    EXPECT_EQ(message, std::string("expected a finite number, got '") + text + "'");
  }
}

TEST(NumberText, RejectsNonIntegers) {
  for (const char* text : {"1.5", "1e3", "", "x", "99999999999999999999"}) {
    std::string message;
    EXPECT_FALSE(parseInteger(text, &message).has_value()) << text;
    EXPECT_EQ(message, std::string("expected an integer, got '") + text + "'");
  }
}

TEST(NumberText, FormatIsShortestAndRoundTripsExactly) {
  EXPECT_EQ(formatDouble(0.1), "0.1");
  EXPECT_EQ(formatDouble(1700000000.123456), "1700000000.123456");
  EXPECT_EQ(formatDouble(-3.0), "-3");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> time(0.0, 2e9);
  std::uniform_real_distribution<double> small(-1e-6, 1e-6);
  for (int i = 0; i < 2000; ++i) {
    for (double value : {time(rng), small(rng)}) {
      std::string message;
      const auto parsed = parseFiniteDouble(formatDouble(value), &message);
      ASSERT_TRUE(parsed.has_value()) << message;
      EXPECT_EQ(*parsed, value);
    }
  }
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(parseFiniteDouble(formatDouble(tiny), nullptr), tiny);
}

}  // namespace
}  // namespace hsmap
