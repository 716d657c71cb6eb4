#include "pipelines/report/report_histogram.h"

#include <algorithm>
#include <cmath>

namespace hsmap {

ReportHistogram binResiduals(std::string name, std::string unit, const std::vector<double>& values,
                             const std::vector<bool>& outlier, double outlier_threshold,
                             std::string outlier_meaning) {
  constexpr int kBins = 40;
  ReportHistogram histogram;
  histogram.name = std::move(name);
  histogram.unit = std::move(unit);
  histogram.outlier_threshold = outlier_threshold;
  histogram.outlier_meaning = std::move(outlier_meaning);
  histogram.counts.assign(kBins, 0);
  histogram.outlier_counts.assign(kBins, 0);

  std::vector<double> sorted;
  sorted.reserve(values.size());
  double sum_squares = 0.0;
  for (double value : values) {
    if (std::isnan(value)) continue;
    sorted.push_back(value);
    sum_squares += value * value;
  }
  histogram.total = (long long)sorted.size();
  if (sorted.empty()) {
    histogram.bin_width = std::isfinite(outlier_threshold) && outlier_threshold > 0 ? outlier_threshold / 20 : 1.0;
    return histogram;
  }
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  histogram.median = n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  histogram.rms = std::sqrt(sum_squares / double(n));
  double upper = sorted[std::size_t(0.99 * double(n - 1))];  // the 99th percentile
  if (std::isfinite(outlier_threshold)) upper = std::max(upper, 2.0 * outlier_threshold);
  if (!(upper > 0.0)) upper = std::max(sorted.back(), 1e-9);
  histogram.bin_width = upper / kBins;

  for (std::size_t i = 0; i < values.size(); ++i) {
    const double value = values[i];
    if (std::isnan(value)) continue;
    const bool is_outlier = i < outlier.size() && outlier[i];
    if (is_outlier) ++histogram.outliers;
    const long long bin = (long long)std::floor(value / histogram.bin_width);
    if (bin >= kBins) {
      ++histogram.beyond;
      if (is_outlier) ++histogram.beyond_outliers;
      continue;
    }
    const std::size_t index = std::size_t(std::max(0LL, bin));
    ++histogram.counts[index];
    if (is_outlier) ++histogram.outlier_counts[index];
  }
  return histogram;
}

}  // namespace hsmap
