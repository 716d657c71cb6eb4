#pragma once
// The report's first section: what ran (run.yaml, or the stage records of a
// run that stopped before writing it), the calibration (calibration.yaml)
// and every warning the run left: calibration.yaml's `warnings` and the
// "warning:" lines of each stage's summary.txt.

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

// Fills survey_folder, variant, program_version, started_utc, run_complete,
// options, stages, total_time_s, peak_rss_mb, calibration, warnings and
// notes. InputError for a malformed file (naming it, the line and the key).
void collectRunSummary(const std::filesystem::path& run, ReportData& data);

}  // namespace hsmap
