#pragma once
// DIR/compare.md: the compare table for people, in Markdown (docs/COMPARE.md):
// the variants' status and sharing, every metric x variant with the best of
// each row in bold and whether lower or higher is better, the stage times per
// variant and the compare's wall time.

#include <filesystem>
#include <string>

#include "pipelines/compare/compare_report_context.h"
#include "pipelines/compare/compare_table.h"

namespace hsmap {

std::string compareMarkdown(const CompareTable& table, const CompareReportContext& context);
// Atomic.
void writeCompareMarkdown(const std::filesystem::path& file, const CompareTable& table,
                          const CompareReportContext& context);

}  // namespace hsmap
