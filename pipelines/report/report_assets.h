#pragma once
// The files RUN/report/index.html is assembled from, carried by the hsmap
// binary itself so that the page opens offline: the plotting libraries
// (vega, vega-lite, vega-embed: minified builds of the versions pinned in
// pipelines/report/web/package-lock.json, installed by `npm ci` at build
// time) and the report's own page template, script and style sheet
// (pipelines/report/web/). The build generates the definition
// (cmake/EmbedWebFiles.cmake).

#include <string_view>

namespace hsmap {

// The text of the embedded file `name`: "vega.min.js", "vega-lite.min.js",
// "vega-embed.min.js", "report.html", "report.js" or "report.css".
// std::logic_error for any other name (a programming error).
std::string_view reportAsset(std::string_view name);

}  // namespace hsmap
