#pragma once
// Medians of a list of numbers, the one statistic many stages summarise
// with (pixel sizes, step times, parallaxes, distances). Both take the list
// by value: std::nth_element reorders it.

#include <vector>

namespace hsmap {

// The median: the middle value of an odd count, the mean of the two middle
// values of an even count; NaN for an empty list.
double median(std::vector<double> values);

// The upper median: the value at index size / 2 once sorted (the middle
// value of an odd count, the larger of the two middle values of an even
// count), which is always one of the values; 0 for an empty list, for
// callers that treat "nothing measured" as zero.
double upperMedian(std::vector<double> values);

}  // namespace hsmap
