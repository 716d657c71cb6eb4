#pragma once
// Bins residuals for the report's histograms (ReportHistogram): the range is
// [0, the larger of the 99th percentile and twice the outlier threshold),
// in 40 bins, and what lies beyond is counted apart, so that a few wild
// residuals do not squeeze the bulk into one bar.

#include <string>
#include <vector>

#include "pipelines/report/report_data.h"

namespace hsmap {

// `values` >= 0 (magnitudes); `outlier[i]` says whether value i is one of the
// robust loss's outliers (empty: none is). NaN values are skipped.
ReportHistogram binResiduals(std::string name, std::string unit, const std::vector<double>& values,
                             const std::vector<bool>& outlier, double outlier_threshold,
                             std::string outlier_meaning);

}  // namespace hsmap
