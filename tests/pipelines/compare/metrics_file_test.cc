// metrics.json for the compare (pipelines/compare/metrics_file.h): the
// scalars in order, null kept as missing, objects and arrays read past.

#include "pipelines/compare/metrics_file.h"

#include <gtest/gtest.h>

#include "core/util/input_error.h"

namespace hsmap {
namespace {

TEST(MetricsFile, ReadsTheScalarsInOrderAndReadsPastTheRest) {
  const MetricFigures figures = parseMetricsJson(
      "{\n  \"variant\": \"joint\",\n  \"rgb_ate_m\": 0.0125,\n  \"ortho_mean_shift_m\": null,\n"
      "  \"uhi_distortion_error\": [0.1, -2e-3],\n  \"timings_s\": {\"frontend\": 12.5, \"total\": 15.9},\n"
      "  \"peak_rss_mb\": 300\n}\n",
      "RUN/metrics.json");
  ASSERT_EQ(figures.size(), 3u);
  EXPECT_EQ(figures[0], (std::pair<std::string, std::optional<double>>{"rgb_ate_m", 0.0125}));
  EXPECT_EQ(figures[1].first, "ortho_mean_shift_m");
  EXPECT_FALSE(figures[1].second);
  EXPECT_EQ(figures[2], (std::pair<std::string, std::optional<double>>{"peak_rss_mb", 300.0}));
}

TEST(MetricsFile, ATruncatedFileIsAnErrorNamingWhere) {
  try {
    parseMetricsJson("{\"rgb_ate_m\": 0.0125,\n \"rgb_scale_error\": ", "RUN/metrics.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "RUN/metrics.json:byte 42: expected more: the file ends here (truncated?)");
  }
}

}  // namespace
}  // namespace hsmap
