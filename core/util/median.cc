#include "core/util/median.h"

#include <algorithm>
#include <cstddef>
#include <limits>

namespace hsmap {

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  // nth_element leaves the smaller half before `middle`: its largest is the
  // lower middle value.
  return 0.5 * (*std::max_element(values.begin(), middle) + *middle);
}

double upperMedian(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace hsmap
