// The hyperspectral ortho-image of the tiny simulated survey, cast with the
// TRUE scan line poses onto the TRUE scene: it must cover the true
// reflectance's footprint, stay inside it and line up with its texture; its
// files must be complete and georeferenced; tiling must not change a value.
#include "pipelines/products/hyperspectral_ortho.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "core/io/envi_reader.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "tests/support/tiny_products_fixture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::tinyProductsSurvey;

struct ProductsRun {
  Survey survey;
  HyperspectralReport report;
};

// Run once for the whole suite (kept for the program's life).
const ProductsRun& defaultRun(const std::filesystem::path& out) {
  static const ProductsRun* run = [&] {
    auto* r = new ProductsRun{loadSurvey(tinyProductsSurvey().folder), {}};
    std::ostringstream log;
    r->report = writeHyperspectralProducts(r->survey, tinyProductsSurvey().true_line_poses,
                                           tinyProductsSurvey().scene_ply, out, HyperspectralOptions{}, log);
    return r;
  }();
  return *run;
}

class HyperspectralOrthoTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { out_ = new testing::TempFolder("hyperspectral-ortho"); }
  static void TearDownTestSuite() {
    delete out_;
    out_ = nullptr;
  }
  static const ProductsRun& run() { return defaultRun(out_->path()); }
  static testing::TempFolder* out_;
};
testing::TempFolder* HyperspectralOrthoTest::out_ = nullptr;

TEST_F(HyperspectralOrthoTest, WritesEveryProductWithUtmMapInfoAndWavelengths) {
  const HyperspectralReport& report = run().report;
  std::cout << report.summary();
  for (const auto& file : {report.ortho_hdr, report.ortho_tif, report.quicklook_png, report.ancillary_hdr}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(file)) << file;
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(out_->path() / "ortho.raw"));
  EXPECT_TRUE(std::filesystem::is_regular_file(out_->path() / "ancillary.raw"));
  const EnviReader ortho(report.ortho_hdr);
  ASSERT_TRUE(ortho.header().map_info.has_value());
  const EnviMapInfo& info = *ortho.header().map_info;
  const UtmProjection projection(run().survey.origin);
  EXPECT_EQ(info.projection, "UTM");
  EXPECT_EQ(info.zone, projection.zone());
  EXPECT_EQ(info.north, projection.northernHemisphere());
  EXPECT_EQ(info.datum, "WGS-84");
  EXPECT_DOUBLE_EQ(info.pixel_size_x, 0.005);
  EXPECT_EQ(ortho.header().wavelength, run().survey.wavelengths_nm);
  EXPECT_EQ(ortho.samples(), report.grid.cols);
  EXPECT_EQ(ortho.lines(), report.grid.rows);
  const EnviReader ancillary(report.ancillary_hdr);
  EXPECT_EQ(ancillary.bands(), 4);
  EXPECT_EQ(ancillary.header().map_info, ortho.header().map_info);
  // Empty pixels are NaN, and both headers declare it for GIS readers.
  const std::pair<std::string, std::string> nan_ignore{"data ignore value", "NaN"};
  EXPECT_EQ(std::count(ortho.header().other_fields.begin(), ortho.header().other_fields.end(), nan_ignore), 1);
  EXPECT_EQ(std::count(ancillary.header().other_fields.begin(), ancillary.header().other_fields.end(), nan_ignore),
            1);
}

TEST_F(HyperspectralOrthoTest, CountsAddUp) {
  const HyperspectralReport& report = run().report;
  EXPECT_EQ(report.lines, std::int64_t(tinyProductsSurvey().true_line_poses.size()));
  EXPECT_EQ(report.pixels_cast, report.hits + report.misses);
  EXPECT_GT(report.hits, 0.95 * report.pixels_cast);
  EXPECT_EQ(report.skipped_non_finite + report.skipped_ignore_value, 0);
  EXPECT_EQ(report.painted, report.hits);  // every hit lands in exactly one tile's own rows
  EXPECT_GT(report.filled_pixels, 0);
  EXPECT_GE(report.fill_radius_px, 1);
  EXPECT_LE(report.fill_radius_px, 4);
  // The central hits advance with the vehicle (plus what its attitude changes add).
  const auto& poses = tinyProductsSurvey().true_line_poses;
  std::vector<double> steps;
  for (std::size_t i = 1; i < poses.size(); ++i) steps.push_back((poses[i].T.t - poses[i - 1].T.t).head<2>().norm());
  std::nth_element(steps.begin(), steps.begin() + std::ptrdiff_t(steps.size() / 2), steps.end());
  EXPECT_NEAR(report.line_spacing_m, steps[steps.size() / 2], 0.3 * steps[steps.size() / 2]);
}

TEST_F(HyperspectralOrthoTest, CoversTheTrueFootprintAndLinesUpWithTheTrueTexture) {
  const OrthoMetrics metrics =
      measureOrtho(run().report.ortho_hdr, tinyProductsSurvey().truth_reflectance_hdr, run().survey.origin);
  std::cout << metrics.summary() << "\n";
  ASSERT_TRUE(metrics.ortho_coverage.value.has_value()) << metrics.ortho_coverage.reason;
  EXPECT_GE(*metrics.ortho_coverage.value, 0.9);
  if (metrics.ortho_mean_shift_m.value) {
    EXPECT_LT(*metrics.ortho_mean_shift_m.value, 0.01);
  } else {
    ADD_FAILURE() << "no registration: " << metrics.ortho_mean_shift_m.reason;
  }
}

TEST_F(HyperspectralOrthoTest, ValidPixelsLieInsideTheTrueFootprint) {
  // Every valid ortho pixel's centre, taken to W, must fall on (or next to:
  // the truth samples the footprint at 1 cm) a valid truth pixel.
  const EnviReader ortho(run().report.ortho_hdr);
  const EnviReader truth(tinyProductsSurvey().truth_reflectance_hdr);
  const EnviMapInfo& t = *truth.header().map_info;
  const UtmProjection projection(run().survey.origin);
  const OrthoGrid& grid = run().report.grid;
  std::vector<std::uint8_t> truth_valid(std::size_t(truth.lines()) * truth.samples());
  Eigen::MatrixXf line;
  for (int r = 0; r < truth.lines(); ++r) {
    truth.readLine(r, line);
    for (int c = 0; c < truth.samples(); ++c) truth_valid[std::size_t(r) * truth.samples() + c] = std::isfinite(line(0, c));
  }
  auto truthValidNear = [&](const Eigen::Vector3d& p_W) {
    const int c = int(std::floor((p_W.y() - t.easting) / t.pixel_size_x));
    const int r = int(std::floor((t.northing - p_W.x()) / t.pixel_size_y));
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int rr = r + dr, cc = c + dc;
        if (rr < 0 || cc < 0 || rr >= truth.lines() || cc >= truth.samples()) continue;
        if (truth_valid[std::size_t(rr) * truth.samples() + cc]) return true;
      }
    }
    return false;
  };
  std::int64_t valid = 0, outside = 0;
  for (int r = 0; r < ortho.lines(); r += 2) {
    ortho.readLine(r, line);
    for (int c = 0; c < ortho.samples(); c += 2) {
      if (!std::isfinite(line(0, c))) continue;
      ++valid;
      if (!truthValidNear(grid.wOfPixel(Eigen::Vector2d(c, r), 0.0, projection))) ++outside;
    }
  }
  ASSERT_GT(valid, 1000);
  EXPECT_LT(double(outside) / double(valid), 0.005) << outside << " of " << valid;
}

TEST_F(HyperspectralOrthoTest, AncillaryValuesArePlausible) {
  const EnviReader ancillary(run().report.ancillary_hdr);
  const EnviReader ortho(run().report.ortho_hdr);
  Eigen::MatrixXf a, o;
  const int lines = ancillary.lines();
  std::int64_t checked = 0;
  for (int r = 0; r < lines; r += 3) {
    ancillary.readLine(r, a);
    ortho.readLine(r, o);
    for (int c = 0; c < ancillary.samples(); ++c) {
      ASSERT_EQ(std::isfinite(a(0, c)), std::isfinite(o(0, c))) << r << " " << c;
      if (!std::isfinite(a(0, c))) continue;
      EXPECT_GE(a(0, c), 0.0f);
      EXPECT_LT(a(0, c), float(run().survey.cube->lines()));
      EXPECT_GE(a(1, c), 0.0f);
      EXPECT_LT(a(1, c), float(run().survey.cube->samples()));
      EXPECT_GT(a(2, c), 0.5f);  // 1.5 m altitude over relief
      EXPECT_LT(a(2, c), 4.0f);
      EXPECT_GE(a(3, c), 0.0f);
      EXPECT_LT(a(3, c), 90.0f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST_F(HyperspectralOrthoTest, SmallTilesGiveTheSameImage) {
  testing::TempFolder out("hyperspectral-tiles");
  HyperspectralOptions options;
  options.tile_memory_mb = 1.0;  // ~20 rows a tile: many tiles
  options.write_geotiff = false;
  options.lines_per_batch = 7;
  // The grid is announced once, before the first tile is written.
  std::vector<OrthoGrid> announced;
  options.on_grid = [&](const OrthoGrid& grid) {
    EXPECT_FALSE(std::filesystem::exists(out / "ortho.raw.partial"));
    announced.push_back(grid);
  };
  std::ostringstream log;
  const HyperspectralReport tiled = writeHyperspectralProducts(
      run().survey, tinyProductsSurvey().true_line_poses, tinyProductsSurvey().scene_ply, out.path(), options, log);
  ASSERT_EQ(announced.size(), 1u);
  EXPECT_EQ(announced[0].cols, tiled.grid.cols);
  EXPECT_EQ(announced[0].rows, tiled.grid.rows);
  EXPECT_EQ(announced[0].mapInfo(), tiled.grid.mapInfo());
  EXPECT_GT(tiled.tiles, 5);
  EXPECT_EQ(tiled.painted, run().report.painted);
  EXPECT_EQ(tiled.filled_pixels, run().report.filled_pixels);
  EXPECT_EQ(testing::TempFolder::read(out / "ortho.raw"), testing::TempFolder::read(out_->path() / "ortho.raw"));
  EXPECT_EQ(testing::TempFolder::read(out / "ancillary.raw"),
            testing::TempFolder::read(out_->path() / "ancillary.raw"));
}

}  // namespace
}  // namespace hsmap
