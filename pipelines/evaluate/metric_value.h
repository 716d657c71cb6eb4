#pragma once
// MetricValue: one figure of metrics.json, or the reason it has none.
//
// The contract (docs/EVALUATE.md) wants every key present and `null` where a
// metric does not apply; a bare null leaves the user guessing whether the
// run failed, the truth lacks something or hsmap cannot measure it yet, so
// a missing value always carries a one-line reason, printed in the table.

#include <optional>
#include <string>
#include <utility>

namespace hsmap {

struct MetricValue {
  std::optional<double> value;
  std::string reason;  // why there is no value (empty when there is one)

  static MetricValue of(double v) { return MetricValue{v, ""}; }
  static MetricValue missing(std::string why) { return MetricValue{std::nullopt, std::move(why)}; }
};

}  // namespace hsmap
