// The report's text encoders: base64 for images and the spectral grid, JSON
// that cannot end its <script> element early, the page's assembly, and the
// calibration's estimated cameras in the page's data.
#include <gtest/gtest.h>

#include <cmath>

#include "pipelines/report/base64_text.h"
#include "pipelines/report/json_text.h"
#include "pipelines/report/report_assets.h"
#include "pipelines/report/report_json.h"
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

// A calibration as joint writes it with self-calibrated UHI intrinsics, and
// georef's RGB intrinsics: each parameter, its 1-sigma, survey.yaml's value
// and the change from it are in the page's data; a camera not estimated is not.
ReportData calibratedReport() {
  ReportData data;
  data.calibration.emplace();
  data.calibration->variant = "joint";
  data.calibration_source = "RUN/calibration.yaml";
  return data;
}

TEST(ReportCalibration, ShowsEachEstimatedCameraWithItsSigmaAndChangeFromTheSurvey) {
  ReportData data = calibratedReport();
  UhiCameraEstimate uhi;
  uhi.f = 1234.5;
  uhi.cx = 240.25;
  uhi.distortion = {0.0125, -0.5};
  uhi.sigma.f = 2.5;
  uhi.sigma.cx = 0.75;
  uhi.sigma.distortion = {0.03125, 0.0};  // k2 held at survey.yaml's
  data.calibration->uhi_camera = uhi;
  RgbCameraEstimate rgb;
  rgb.fx = 801.5;
  rgb.fy = 799.25;
  rgb.cx = 322.75;
  rgb.cy = 181.0;
  rgb.distortion = {-0.0625, 0.015625, 0.0, 0.0, 0.0};
  rgb.sigma.fx = 1.5;
  rgb.sigma.fy = 1.25;
  rgb.sigma.cx = 2.125;
  rgb.sigma.cy = 1.875;
  rgb.sigma.distortion = {0.005, 0.0025, 0.0, 0.0, 0.0};
  data.calibration->rgb_camera = rgb;
  data.survey_uhi_camera = PushbroomParameters{480, 1222.0, 240.25, {0.0, -0.5}};
  data.survey_rgb_camera = PinholeRadtanParameters{640, 360, 800.0, 800.0, 320.0, 180.0, {-0.0625, 0.0, 0.0, 0.0, 0.0}};
  const std::string page = assembleReportPage("run", reportJson(data));

  EXPECT_NE(page.find("{\"key\":\"uhi_camera\",\"name\":\"UHI push-broom camera"), std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"f\",\"unit\":\"px\",\"estimate\":1234.5,\"sigma\":2.5,\"survey\":1222,"
                      "\"change\":12.5}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"cx\",\"unit\":\"px\",\"estimate\":240.25,\"sigma\":0.75,\"survey\":240.25,"
                      "\"change\":null}"),
            std::string::npos)
      << "no change where the estimate is survey.yaml's value";
  EXPECT_NE(page.find("{\"name\":\"k1\",\"unit\":\"\",\"estimate\":0.0125,\"sigma\":0.03125,\"survey\":0,"
                      "\"change\":0.0125}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"k2\",\"unit\":\"\",\"estimate\":-0.5,\"sigma\":0,\"survey\":-0.5,"
                      "\"change\":null}"),
            std::string::npos);

  EXPECT_NE(page.find("{\"key\":\"rgb_camera\",\"name\":\"RGB camera"), std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"fx\",\"unit\":\"px\",\"estimate\":801.5,\"sigma\":1.5,\"survey\":800,"
                      "\"change\":1.5}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"fy\",\"unit\":\"px\",\"estimate\":799.25,\"sigma\":1.25,\"survey\":800,"
                      "\"change\":-0.75}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"cy\",\"unit\":\"px\",\"estimate\":181,\"sigma\":1.875,\"survey\":180,"
                      "\"change\":1}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"k2\",\"unit\":\"\",\"estimate\":0.015625,\"sigma\":0.0025,\"survey\":0,"
                      "\"change\":0.015625}"),
            std::string::npos);
  EXPECT_NE(page.find("{\"name\":\"k3\",\"unit\":\"\",\"estimate\":0,\"sigma\":0,\"survey\":0,\"change\":null}"),
            std::string::npos);
  // The page's script draws a table per camera from this list.
  EXPECT_NE(page.find("c.cameras"), std::string::npos);
  EXPECT_NE(page.find("change from survey.yaml"), std::string::npos);

  // Without survey.yaml's cameras (the survey was not read): the estimate and its sigma, no change.
  data.survey_uhi_camera.reset();
  const std::string unread = reportJson(data);
  EXPECT_NE(unread.find("{\"name\":\"f\",\"unit\":\"px\",\"estimate\":1234.5,\"sigma\":2.5,\"survey\":null,"
                        "\"change\":null}"),
            std::string::npos);
}

TEST(ReportCalibration, ShowsNoCameraThatWasNotEstimated) {
  ReportData data = calibratedReport();
  data.survey_uhi_camera = PushbroomParameters{480, 1222.0, 240.25, {0.0, 0.0}};
  data.survey_rgb_camera = PinholeRadtanParameters{640, 360, 800.0, 800.0, 320.0, 180.0, {0.0, 0.0, 0.0, 0.0, 0.0}};
  const std::string page = assembleReportPage("run", reportJson(data));
  EXPECT_NE(page.find("\"cameras\":[]"), std::string::npos);
  EXPECT_EQ(page.find("\"key\":\"uhi_camera\""), std::string::npos);
  EXPECT_EQ(page.find("\"key\":\"rgb_camera\""), std::string::npos);
  EXPECT_EQ(page.find("\"estimate\":"), std::string::npos);

  // Only the RGB camera estimated: only its table.
  data.calibration->rgb_camera = RgbCameraEstimate{};
  const std::string rgb_only = reportJson(data);
  EXPECT_NE(rgb_only.find("\"key\":\"rgb_camera\""), std::string::npos);
  EXPECT_EQ(rgb_only.find("\"key\":\"uhi_camera\""), std::string::npos);
}

}  // namespace
}  // namespace hsmap
