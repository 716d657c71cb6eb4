// compare.html (pipelines/compare/compare_html.h): one page that needs
// nothing else, the best of each row marked, the quick-looks embedded.

#include "pipelines/compare/compare_html.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "pipelines/compare/compare_markdown.h"
#include "pipelines/compare/image_data_uri.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

CompareTable table(const std::filesystem::path& quicklook) {
  VariantOutcome planar, sequential;
  planar.variant = "planar";
  planar.metrics = {{"rgb_ate_m", 0.0748}, {"mesh_completeness", 0.0}};
  sequential.variant = "sequential";
  sequential.metrics = {{"rgb_ate_m", 0.0646}, {"mesh_completeness", 0.99}};
  sequential.quicklook = quicklook;
  sequential.stages = {{"frontend", 3.0}};
  return buildCompareTable({planar, sequential});
}

TEST(CompareHtml, IsSelfContainedWithTheBestMarkedAndTheQuicklookEmbedded) {
  const testing::TempFolder temp;
  const auto image = temp / "ortho_rgb.png";
  cv::imwrite(image.string(), cv::Mat(3000, 400, CV_8UC4, cv::Scalar(10, 200, 30, 255)));
  const CompareReportContext context{"/data/dive7", "/runs/dive7", 123.4, true};
  const std::string html = compareHtml(table(image), context);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"data:image/png;base64,"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num best\" title=\"best of the row\">0.0646 &#9733;</td>"), std::string::npos)
      << html.substr(0, 4000);
  EXPECT_NE(html.find("<td class=\"better\">higher</td>"), std::string::npos);
  EXPECT_NE(html.find("123.4 s"), std::string::npos);
  EXPECT_LT(html.size(), 400'000u);  // the 400 x 3000 quick-look shrunk to 900 pixels high
}

TEST(CompareMarkdown, MarksTheBestInBoldAndSaysWhichWayIsBetter) {
  const CompareReportContext context{"/data/dive7", "/runs/dive7", 123.4, true};
  const std::string markdown = compareMarkdown(table(""), context);
  EXPECT_NE(markdown.find("| `rgb_ate_m` | lower | 0.0748 | **0.0646** |"), std::string::npos) << markdown;
  EXPECT_NE(markdown.find("| `mesh_completeness` | higher | 0 | **0.99** |"), std::string::npos) << markdown;
}

TEST(ImageDataUri, Base64IsRfc4648) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(imageDataUri("/no/such/image.png", 100), "");
}

}  // namespace
}  // namespace hsmap
