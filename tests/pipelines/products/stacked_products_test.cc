// The stacked variant's products: the cube's lines side by side, invalid
// spectra NaN (counted), no map position.
#include "pipelines/products/stacked_products.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

constexpr int kSamples = 40, kLines = 12, kBands = 5;
constexpr float kIgnore = -1.0f;

// value(line, band, sample): distinct for every cell.
float value(int l, int b, int s) { return float(1000 * l + 100 * b + s); }

// A float32 BIP cube (the products are BIL) whose line 3, sample 7 holds the
// data ignore value in every band and line 5, sample 9 a NaN in band 2.
std::filesystem::path writeCube(const std::filesystem::path& folder) {
  EnviHeader header;
  header.samples = kSamples;
  header.lines = kLines;
  header.bands = kBands;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bip;
  header.wavelength = {450, 500, 550, 600, 650};
  header.wavelength_units = "Nanometers";
  header.other_fields.emplace_back("data ignore value", "-1");
  const std::filesystem::path hdr = folder / "cube.hdr";
  EnviWriter writer(hdr, header);
  std::vector<float> line(std::size_t(kBands) * kSamples);
  for (int l = 0; l < kLines; ++l) {
    for (int b = 0; b < kBands; ++b) {
      for (int s = 0; s < kSamples; ++s) line[std::size_t(b) * kSamples + s] = value(l, b, s);
    }
    if (l == 3) {
      for (int b = 0; b < kBands; ++b) line[std::size_t(b) * kSamples + 7] = kIgnore;
    }
    if (l == 5) line[std::size_t(2) * kSamples + 9] = std::numeric_limits<float>::quiet_NaN();
    writer.writeLine(line.data());
  }
  writer.finish();
  return hdr;
}

TEST(StackedProducts, AreTheLinesSideBySideWithInvalidSpectraNaNAndNoMapPosition) {
  testing::TempFolder folder;
  const EnviReader cube(writeCube(folder.path()));
  std::ostringstream log;
  const StackedReport report =
      writeStackedProducts(cube, {450, 500, 550, 600, 650}, folder.path() / "hyperspectral", log);
  EXPECT_EQ(report.skipped_ignore_value, 1);
  EXPECT_EQ(report.skipped_non_finite, 1);

  const EnviReader ortho(report.ortho_hdr);
  EXPECT_EQ(ortho.lines(), kLines);
  EXPECT_EQ(ortho.samples(), kSamples);
  EXPECT_EQ(ortho.bands(), kBands);
  EXPECT_FALSE(ortho.header().map_info.has_value());
  EXPECT_EQ(ortho.header().wavelength, (std::vector<double>{450, 500, 550, 600, 650}));
  // The cube's ignore value (-1) is not the product's: its invalid spectra are NaN.
  const std::pair<std::string, std::string> nan_ignore{"data ignore value", "NaN"};
  EXPECT_EQ(ortho.header().other_fields, (std::vector<std::pair<std::string, std::string>>{nan_ignore}));
  std::vector<float> line(std::size_t(kBands) * kSamples);
  for (int l = 0; l < kLines; ++l) {
    ortho.readLine(l, line.data());
    for (int b = 0; b < kBands; ++b) {
      for (int s = 0; s < kSamples; ++s) {
        const float got = line[std::size_t(b) * kSamples + s];
        if ((l == 3 && s == 7) || (l == 5 && s == 9)) {
          EXPECT_TRUE(std::isnan(got)) << l << " " << b << " " << s;  // the whole spectrum
        } else {
          ASSERT_EQ(got, value(l, b, s)) << l << " " << b << " " << s;
        }
      }
    }
  }
  const EnviReader ancillary(report.ancillary_hdr);
  ASSERT_EQ(ancillary.bands(), 4);
  std::vector<float> extra(std::size_t(4) * kSamples);
  ancillary.readLine(6, extra.data());
  EXPECT_EQ(extra[11], 6.0f);                    // scan line
  EXPECT_EQ(extra[std::size_t(kSamples) + 11], 11.0f);  // sample
  EXPECT_TRUE(std::isnan(extra[std::size_t(2) * kSamples + 11]));  // nothing cast: no range
  const cv::Mat png = cv::imread(report.quicklook_png.string());
  EXPECT_EQ(png.rows, kLines);
  EXPECT_EQ(png.cols, kSamples);
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "hyperspectral" / "ortho.tif"));
}

TEST(StackedProducts, RejectsWavelengthsNotMatchingTheBands) {
  testing::TempFolder folder;
  const EnviReader cube(writeCube(folder.path()));
  std::ostringstream log;
  EXPECT_THROW(writeStackedProducts(cube, {450, 500}, folder.path() / "out", log), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
