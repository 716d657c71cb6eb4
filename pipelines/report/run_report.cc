#include "pipelines/report/run_report.h"

#include "core/io/atomic_file.h"
#include "pipelines/report/collect_report_data.h"
#include "pipelines/report/report_json.h"
#include "pipelines/report/report_page.h"

namespace hsmap {

namespace fs = std::filesystem;

fs::path runReportPath(const fs::path& run) { return run / kRunReportPath; }

RunReport writeRunReport(const fs::path& run) {
  const ReportData data = collectReportData(run);
  const std::string title = "hsmap report: " + (data.survey_name.empty() ? data.survey_folder : data.survey_name) +
                            ", " + data.variant;
  const std::string page = assembleReportPage(title, reportJson(data));
  RunReport report;
  report.path = runReportPath(run);
  fs::create_directories(report.path.parent_path());
  writeTextAtomically(report.path, page);
  report.bytes = page.size();
  report.notes = data.notes;
  return report;
}

}  // namespace hsmap
