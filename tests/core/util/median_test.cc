#include "core/util/median.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace hsmap {
namespace {

TEST(Median, OddCountIsTheMiddleValueWhateverTheOrder) {
  EXPECT_DOUBLE_EQ(median({5.0, -1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(upperMedian({5.0, -1.0, 3.0}), 3.0);
}

TEST(Median, EvenCountAveragesTheTwoMiddleValuesAndTheUpperMedianTakesTheLarger) {
  const std::vector<double> values{10.0, 1.0, 4.0, 2.0};  // sorted: 1 2 4 10
  EXPECT_DOUBLE_EQ(median(values), 3.0);
  EXPECT_DOUBLE_EQ(upperMedian(values), 4.0);
}

TEST(Median, RepeatedMiddleValues) {
  EXPECT_DOUBLE_EQ(median({2.0, 7.0, 2.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(upperMedian({2.0, 7.0, 2.0, 2.0}), 2.0);
}

TEST(Median, EmptyListIsNaNForTheMedianAndZeroForTheUpperMedian) {
  EXPECT_TRUE(std::isnan(median({})));
  EXPECT_EQ(upperMedian({}), 0.0);
}

TEST(Median, OneValueIsItself) {
  EXPECT_DOUBLE_EQ(median({-2.5}), -2.5);
  EXPECT_DOUBLE_EQ(upperMedian({-2.5}), -2.5);
}

}  // namespace
}  // namespace hsmap
