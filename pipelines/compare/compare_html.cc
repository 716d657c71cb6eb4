#include "pipelines/compare/compare_html.h"

#include <sstream>

#include "core/io/atomic_file.h"
#include "pipelines/compare/image_data_uri.h"

namespace hsmap {

namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

constexpr const char* kStyle = R"(<style>
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.best { background: #d8f5d0; font-weight: bold; }
td.failed, th.failed { color: #a00; }
td.key { font-family: monospace; }
td.better { color: #555; }
.quicklooks { display: flex; flex-wrap: wrap; gap: 1em; align-items: flex-start; }
.quicklooks figure { margin: 0; text-align: center; }
.quicklooks img { border: 1px solid #ccc; max-height: 900px; background: repeating-conic-gradient(#eee 0 25%, #fff 0 50%) 0 0 / 16px 16px; }
</style>
)";

void headerRow(std::ostringstream& out, const CompareTable& table, const std::string& first, bool with_better) {
  out << "<tr><th>" << first << "</th>" << (with_better ? "<th>better</th>" : "");
  for (const VariantOutcome& variant : table.variants) {
    out << "<th" << (variant.succeeded() ? "" : " class=\"failed\"") << ">" << escaped(variant.variant) << "</th>";
  }
  out << "</tr>\n";
}

void figureRows(std::ostringstream& out, const std::vector<CompareRow>& rows) {
  for (const CompareRow& row : rows) {
    out << "<tr><td class=\"key\">" << escaped(row.key) << "</td><td class=\"better\">" << toString(row.better)
        << "</td>";
    for (std::size_t c = 0; c < row.values.size(); ++c) {
      out << "<td class=\"num" << (row.best[c] ? " best" : "") << "\""
          << (row.best[c] ? " title=\"best of the row\"" : "") << ">" << displayFigure(row.values[c])
          << (row.best[c] ? " &#9733;" : "") << "</td>";
    }
    out << "</tr>\n";
  }
}

}  // namespace

std::string compareHtml(const CompareTable& table, const CompareReportContext& context) {
  std::ostringstream out;
  const std::string name = escaped(context.survey.filename().string());
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>hsmap compare: " << name
      << "</title>\n"
      << kStyle << "</head>\n<body>\n<h1>hsmap compare: " << name << "</h1>\n";
  out << "<p>Survey <code>" << escaped(context.survey.string()) << "</code>; each variant's run is in <code>"
      << escaped((context.out / "VARIANT").string()) << "</code>, its log in <code>"
      << escaped((context.out / "VARIANT.log").string()) << "</code>. The whole compare took <b>"
      << displayFigure(context.wall_time_s) << " s</b>.</p>\n";

  out << "<h2>Variants</h2>\n<table>\n";
  headerRow(out, table, "variant", false);
  out << "<tr><td>status</td>";
  for (const VariantOutcome& variant : table.variants) {
    out << "<td" << (variant.succeeded() ? "" : " class=\"failed\"") << ">" << escaped(variant.status) << "</td>";
  }
  out << "</tr>\n<tr><td>stages shared</td>";
  for (const VariantOutcome& variant : table.variants) {
    std::string shared;
    for (const std::string& stage : variant.shared_stages) shared += (shared.empty() ? "" : ", ") + stage;
    out << "<td>" << (shared.empty() ? "—" : escaped(shared + " (from " + variant.shared_from + ")")) << "</td>";
  }
  out << "</tr>\n</table>\n";

  out << "<h2>Metrics</h2>\n";
  if (!context.evaluated) {
    out << "<p>The survey has no <code>truth/</code>: nothing to evaluate.</p>\n";
  } else if (table.metric_rows.empty()) {
    out << "<p>No variant was evaluated.</p>\n";
  } else {
    out << "<p>Every figure of the variants' <code>metrics.json</code> (docs/EVALUATE.md). The best of each row "
           "is marked &#9733; on green; <i>better</i> says whether lower or higher is better (empty: a figure of "
           "the survey and its truth, the same for every variant, with no best). — is a figure that does not "
           "apply or a variant that failed.</p>\n<table>\n";
    headerRow(out, table, "metric", true);
    figureRows(out, table.metric_rows);
    out << "</table>\n";
  }

  out << "<h2>Ortho-images (quick-looks)</h2>\n<div class=\"quicklooks\">\n";
  for (const VariantOutcome& variant : table.variants) {
    const std::string uri = imageDataUri(variant.quicklook, kQuicklookMaxSide);
    out << "<figure>";
    if (uri.empty()) {
      out << "<p>(no quick-look)</p>";
    } else {
      out << "<img src=\"" << uri << "\" alt=\"" << escaped(variant.variant) << " quick-look\">";
    }
    out << "<figcaption>" << escaped(variant.variant) << "</figcaption></figure>\n";
  }
  out << "</div>\n";

  out << "<h2>Times (s)</h2>\n<p><i>wall_time_s</i> is the variant's run and evaluation in this compare; "
         "<i>time_s.&lt;stage&gt;</i> each stage's time from its run.yaml (a shared stage ran once, in the "
         "variant it is shared from).</p>\n<table>\n";
  headerRow(out, table, "time", true);
  figureRows(out, table.time_rows);
  out << "</table>\n</body>\n</html>\n";
  return out.str();
}

void writeCompareHtml(const std::filesystem::path& file, const CompareTable& table,
                      const CompareReportContext& context) {
  AtomicFile out(file);
  out.stream() << compareHtml(table, context);
  out.commit();
}

}  // namespace hsmap
