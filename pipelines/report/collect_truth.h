#pragma once
// The section shown when the run was scored against a truth (`hsmap
// evaluate`): metrics.json as a table and the ortho-image's local
// displacements (report/ortho_patches.csv, written by evaluate) as a vector
// map. Without metrics.json the section says how to get it.

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

// Fills metrics (every number of metrics.json in its order; nested objects
// and lists flattened as "timings_s.total", "uhi_distortion_error[0]";
// null kept as nullopt) and ortho_patches. InputError for a malformed file.
void collectTruth(const std::filesystem::path& run, ReportData& data);

}  // namespace hsmap
