#pragma once
// The report page: web/report.html with the style sheet, the plotting
// libraries, the run's data (report_json.h) and the page's script inlined,
// one file that needs nothing beside it. The page's Content-Security-Policy
// allows no request at all (images are data: URIs, scripts and styles
// inline), so even a library reaching out would be stopped by the browser.

#include <string>
#include <string_view>

namespace hsmap {

// `title`: the page's title; `data_json`: reportJson()'s text.
std::string assembleReportPage(std::string_view title, std::string_view data_json);

}  // namespace hsmap
