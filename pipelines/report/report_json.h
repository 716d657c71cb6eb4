#pragma once
// ReportData as the JSON object the report page's script (web/report.js)
// reads. Its keys are that script's contract: a key renamed here is renamed
// there.

#include <string>

#include "pipelines/report/report_data.h"

namespace hsmap {

std::string reportJson(const ReportData& data);

}  // namespace hsmap
