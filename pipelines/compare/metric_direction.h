#pragma once
// Which way is better for each figure of metrics.json (docs/EVALUATE.md), so
// that the compare table can mark the best variant of a row:
//   lower   errors, RMS, spectral angles, scale errors, times, memory;
//   higher  the fractions covered: mesh_completeness (and its aligned
//           twins), ortho_coverage;
//   none    figures of the survey and its truth, the same for every variant
//           (the INS floor, the track's cross-track spread, the view
//           distance h), and any key this hsmap does not know: no best.

#include <string>

namespace hsmap {

enum class Better { lower, higher, none };

Better metricDirection(const std::string& key);
// "lower", "higher", "" (none).
const char* toString(Better better);
// The inverse of toString(Better); std::invalid_argument for other texts.
Better parseBetter(const std::string& text);

}  // namespace hsmap
