#include "pipelines/report/collect_truth.h"

#include "core/io/results_folder.h"
#include "core/survey/number_text.h"
#include "core/survey/strict_yaml_map.h"
#include "core/util/input_error.h"
#include "pipelines/report/named_csv.h"

namespace hsmap {

namespace fs = std::filesystem;

namespace {

// metrics.json is JSON, which yaml-cpp reads as YAML's flow style.
void flattenMetric(const fs::path& file, const std::string& key, const YAML::Node& node, ReportData& data) {
  if (node.IsNull()) {
    data.metrics.emplace_back(key, std::nullopt);
  } else if (node.IsScalar()) {
    std::string message;
    const std::optional<double> value = parseFiniteDouble(node.Scalar(), &message);
    if (!value) {
      throw InputError(file, InputError::atLine(node.Mark().line + 1) + ", " + InputError::atKey(key),
                       "expected a number or null, got '" + node.Scalar() + "'");
    }
    data.metrics.emplace_back(key, value);
  } else if (node.IsMap()) {
    for (const auto& entry : node) flattenMetric(file, key + "." + entry.first.Scalar(), entry.second, data);
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) flattenMetric(file, key + "[" + std::to_string(i) + "]", node[i], data);
  }
}

}  // namespace

void collectTruth(const fs::path& run, ReportData& data) {
  std::error_code error;
  const fs::path metrics = run / results_paths::metrics_json;
  if (!fs::is_regular_file(metrics, error)) {
    data.notes.push_back("no metrics: " + metrics.string() +
                         " is missing (on a simulated survey, `hsmap evaluate RUN --truth SURVEY/truth` scores the "
                         "run and adds its metrics and the ortho displacement field to this report)");
    return;
  }
  const YAML::Node root = loadYamlFile(metrics);
  if (!root.IsMap()) throw InputError(metrics, "", "expected a JSON object of metrics");
  for (const auto& entry : root) {
    const std::string key = entry.first.Scalar();
    if (key == "variant") continue;  // a text, shown in the run's section
    flattenMetric(metrics, key, entry.second, data);
  }

  const fs::path patches = run / results_paths::report_dir / "ortho_patches.csv";
  if (!fs::is_regular_file(patches, error)) {
    data.notes.push_back("no ortho displacement field: " + patches.string() +
                         " is missing (evaluate writes it when the run has a hyperspectral ortho-image)");
    return;
  }
  const NamedCsv table(patches, {"north_m", "east_m", "displacement_north_m", "displacement_east_m", "response"});
  for (std::size_t row = 0; row < table.rowCount(); ++row) {
    data.ortho_patches.push_back({table.number(row, "north_m"), table.number(row, "east_m"),
                                  table.number(row, "displacement_north_m"), table.number(row, "displacement_east_m"),
                                  table.number(row, "response")});
  }
}

}  // namespace hsmap
