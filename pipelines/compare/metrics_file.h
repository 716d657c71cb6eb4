#pragma once
// Reads RUN/metrics.json (docs/EVALUATE.md) for the compare table: its scalar
// figures, in the file's order, each a number or null. The variant's name,
// the timings object and any array are read past (the table takes the stage
// times from run.yaml). Strict JSON: anything else is an InputError naming
// the file, the byte offset and what was expected.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace hsmap {

using MetricFigures = std::vector<std::pair<std::string, std::optional<double>>>;

MetricFigures readMetricsFile(const std::filesystem::path& file);
// The same on the file's content; `file` names it in errors.
MetricFigures parseMetricsJson(std::string_view text, const std::filesystem::path& file);

}  // namespace hsmap
