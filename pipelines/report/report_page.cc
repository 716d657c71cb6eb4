#include "pipelines/report/report_page.h"

#include <stdexcept>

#include "pipelines/report/json_text.h"
#include "pipelines/report/report_assets.h"

namespace hsmap {

namespace {

// `text` with the one `placeholder` of the template replaced.
void fill(std::string& page, std::string_view placeholder, std::string_view text) {
  const std::size_t at = page.find(placeholder);
  if (at == std::string::npos || page.find(placeholder, at + 1) != std::string::npos) {
    throw std::logic_error("assembleReportPage: web/report.html must hold '" + std::string(placeholder) +
                           "' exactly once");
  }
  page.replace(at, placeholder.size(), text);
}

// A script's text made safe inside <script>: only "</script" could end the
// element early; "<\/script" means the same in JavaScript strings and regexes.
std::string scriptElement(std::string_view code) {
  std::string text(code);
  for (std::size_t at = text.find("</script"); at != std::string::npos; at = text.find("</script", at)) {
    text.insert(at + 1, "\\");
  }
  return "<script>" + text + "</script>\n";
}

// The text of a title in HTML.
std::string htmlText(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string assembleReportPage(std::string_view title, std::string_view data_json) {
  std::string page(reportAsset("report.html"));
  fill(page, "<!--hsmap:title-->", htmlText(title));
  fill(page, "/*hsmap:style*/", reportAsset("report.css"));
  std::string libraries;
  for (const char* name : {"vega.min.js", "vega-lite.min.js", "vega-embed.min.js"}) {
    libraries += scriptElement(reportAsset(name));
  }
  fill(page, "<!--hsmap:libraries-->", libraries);
  // jsonString() already wrote '<' as \u003c: the data cannot end its element.
  fill(page, "<!--hsmap:data-->",
       "<script type=\"application/json\" id=\"hsmap-data\">" + std::string(data_json) + "</script>\n");
  fill(page, "<!--hsmap:script-->", scriptElement(reportAsset("report.js")));
  return page;
}

}  // namespace hsmap
