#pragma once
// Everything the report shows, collected from a run folder: the run's
// summary, the trajectory, the residuals, the images and, after `hsmap
// evaluate`, the metrics. The survey is the one run.yaml (or a stage record)
// names; when it cannot be read (moved, deleted) the parts that need it (the
// INS fixes, the residuals) are left out and a note says why.

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

// InputError for a malformed file of the run folder (naming the file, the
// line or key); std::runtime_error when `run` is not a run folder.
ReportData collectReportData(const std::filesystem::path& run);

}  // namespace hsmap
