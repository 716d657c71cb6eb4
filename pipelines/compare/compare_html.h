#pragma once
// DIR/compare.html: the compare on one self-contained page that opens
// offline (docs/COMPARE.md): no script, no style sheet, font or image from
// elsewhere; the ortho-images' quick-looks are embedded as data: URIs,
// shrunk (image_data_uri.h). Sections: the variants (status, stages shared,
// wall time), every metric x variant with the best of each row marked and
// whether lower or higher is better, the quick-looks side by side, the stage
// times per variant and the compare's wall time.

#include <filesystem>
#include <string>

#include "pipelines/compare/compare_report_context.h"
#include "pipelines/compare/compare_table.h"

namespace hsmap {

// The quick-looks' longer side on the page (pixels).
inline constexpr int kQuicklookMaxSide = 900;

std::string compareHtml(const CompareTable& table, const CompareReportContext& context);
// Atomic.
void writeCompareHtml(const std::filesystem::path& file, const CompareTable& table,
                      const CompareReportContext& context);

}  // namespace hsmap
