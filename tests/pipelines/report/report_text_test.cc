// The report's text encoders: base64 for images and the spectral grid, JSON
// that cannot end its <script> element early, and the page's assembly.
#include <gtest/gtest.h>

#include <cmath>

#include "pipelines/report/base64_text.h"
#include "pipelines/report/json_text.h"
#include "pipelines/report/report_assets.h"
#include "pipelines/report/report_page.h"

namespace hsmap {
namespace {

TEST(Base64Encode, MatchesRfc4648TestVectors) {
  EXPECT_EQ(base64Encode(""), "");
  EXPECT_EQ(base64Encode("f"), "Zg==");
  EXPECT_EQ(base64Encode("fo"), "Zm8=");
  EXPECT_EQ(base64Encode("foo"), "Zm9v");
  EXPECT_EQ(base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64Encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64Encode(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(JsonText, EscapesWhatCouldEndAScriptElementAndWritesNaNAsNull) {
  JsonText json;
  json.beginObject().key("warning").value("a </script> <b> & \"q\"\n").key("x").value(0.1).key("nan").value(NAN);
  json.key("list").beginArray().value(1LL).value(true).null().endArray().endObject();
  EXPECT_EQ(json.text(),
            "{\"warning\":\"a \\u003c/script\\u003e \\u003cb\\u003e \\u0026 \\\"q\\\"\\n\",\"x\":0.1,\"nan\":null,"
            "\"list\":[1,true,null]}");
}

TEST(AssembleReportPage, InlinesEverythingAndKeepsTheDataInsideItsElement) {
  const std::string page = assembleReportPage("run <1>", JsonText().beginObject().key("w").value("</script>").endObject().text());
  EXPECT_NE(page.find("<title>run &lt;1&gt;</title>"), std::string::npos);
  EXPECT_EQ(page.find("hsmap:"), std::string::npos) << "a placeholder was left";
  EXPECT_NE(page.find("<script type=\"application/json\" id=\"hsmap-data\">{\"w\":\"\\u003c/script\\u003e\"}</script>"),
            std::string::npos);
  // The template links to nothing: no src= or href= at all (scripts, styles and data are inline).
  const std::string_view template_text = reportAsset("report.html");
  EXPECT_EQ(template_text.find("src="), std::string::npos);
  EXPECT_EQ(template_text.find("href="), std::string::npos);
  EXPECT_NE(page.find("default-src 'none'"), std::string::npos);  // the page's Content-Security-Policy
  EXPECT_NE(page.find("vegaEmbed"), std::string::npos);
}

}  // namespace
}  // namespace hsmap
