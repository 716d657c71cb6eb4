#include "pipelines/compare/compare_markdown.h"

#include <sstream>

#include "core/io/atomic_file.h"

namespace hsmap {

namespace {

// A cell's text: '|' would end the cell, a line break the row.
std::string cell(std::string text) {
  std::string escaped;
  for (char c : text) {
    if (c == '|') escaped += "\\|";
    else if (c == '\n' || c == '\r') escaped += ' ';
    else escaped += c;
  }
  return escaped;
}

void header(std::ostringstream& out, const CompareTable& table, const std::string& first, bool with_better) {
  out << "| " << first << " |" << (with_better ? " better |" : "");
  for (const VariantOutcome& variant : table.variants) out << " " << variant.variant << " |";
  out << "\n|---|" << (with_better ? "---|" : "");
  for (std::size_t i = 0; i < table.variants.size(); ++i) out << "---:|";
  out << "\n";
}

void rows(std::ostringstream& out, const std::vector<CompareRow>& rows) {
  for (const CompareRow& row : rows) {
    out << "| `" << row.key << "` | " << toString(row.better) << " |";
    for (std::size_t c = 0; c < row.values.size(); ++c) {
      const std::string figure = displayFigure(row.values[c]);
      out << " " << (row.best[c] ? "**" + figure + "**" : figure) << " |";
    }
    out << "\n";
  }
}

}  // namespace

std::string compareMarkdown(const CompareTable& table, const CompareReportContext& context) {
  std::ostringstream out;
  out << "# hsmap compare: " << context.survey.filename().string() << "\n\n";
  out << "Survey `" << context.survey.string() << "`; each variant's run is in `"
      << (context.out / "VARIANT").string() << "`, its log in `" << (context.out / "VARIANT.log").string()
      << "`. The whole compare took " << displayFigure(context.wall_time_s) << " s.\n\n";

  header(out, table, "variant", false);
  out << "| status |";
  for (const VariantOutcome& variant : table.variants) out << " " << cell(variant.status) << " |";
  out << "\n| stages shared |";
  for (const VariantOutcome& variant : table.variants) {
    std::string shared;
    for (const std::string& stage : variant.shared_stages) shared += (shared.empty() ? "" : ", ") + stage;
    out << " " << (shared.empty() ? "—" : cell(shared + " (from " + variant.shared_from + ")")) << " |";
  }
  out << "\n\n";

  out << "## Metrics\n\n";
  if (!context.evaluated) {
    out << "The survey has no `truth/`: nothing to evaluate.\n\n";
  } else if (table.metric_rows.empty()) {
    out << "No variant was evaluated.\n\n";
  } else {
    out << "Every figure of the variants' `metrics.json` (docs/EVALUATE.md). The best of each row is in "
           "**bold**; `better` says whether lower or higher is better (empty: a figure of the survey and its "
           "truth, the same for every variant, with no best). — is a figure that does not apply or a "
           "variant that failed.\n\n";
    header(out, table, "metric", true);
    rows(out, table.metric_rows);
    out << "\n";
  }

  out << "## Times (s)\n\n";
  out << "`wall_time_s` is the variant's run and evaluation in this compare; `time_s.<stage>` each stage's "
         "time from its `run.yaml` (a shared stage ran once, in the variant it is shared from).\n\n";
  header(out, table, "time", true);
  rows(out, table.time_rows);
  return out.str();
}

void writeCompareMarkdown(const std::filesystem::path& file, const CompareTable& table,
                          const CompareReportContext& context) {
  AtomicFile out(file);
  out.stream() << compareMarkdown(table, context);
  out.commit();
}

}  // namespace hsmap
