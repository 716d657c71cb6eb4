// The ortho-image metrics through `hsmap evaluate` (evaluateRunFolder): a
// hand-made RUN/hyperspectral/ortho.hdr in UTM (4 mm pixels) against a
// textured truth/reflectance.hdr in W (the fixture's footprint at 5 mm:
// 400 x 400 pixels over north [0.5, 2.5] x east [-1, 1], NaN east of 0.8 m
// and west of -0.8 m), both showing one smooth texture defined in W; the
// product is written through UtmProjection at the survey origin, as the
// products stage would. (The resolutions are those of ortho_metrics_test.cc,
// whose noise floor ortho_metrics.h reports.)
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <regex>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/geometry/utm_projection.h"
#include "core/io/envi_writer.h"
#include "core/io/results_folder.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/evaluate_run.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"
#include "tests/pipelines/evaluate/smooth_texture.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;

constexpr int kBands = 4;  // as the fixture's truth
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// The truth raster (replacing the fixture's, on the same footprint).
constexpr double kTruthPixel = 0.005;
constexpr int kTruthSide = 400, kTruthNanColumns = 40;
constexpr double kTruthNorthMax = 2.5, kTruthEastMin = -1.0;
constexpr double kOrthoPixel = 0.004;

// Textures over north [0, 3] x east [-1.5, 1.5] m (smooth_texture.h).
using Texture = testing::SmoothTexture;

// Two materials mixed by two textures, so that the spectra's direction varies.
Eigen::VectorXf seabed(double north, double east) {
  static const Texture texture_a(5, 0.0, -1.5, 1200, 1200), texture_b(9, 0.0, -1.5, 1200, 1200);
  const Eigen::Vector4d a(0.2, 0.4, 0.6, 0.3), b(0.5, 0.3, 0.1, 0.4);
  return ((1.0 + 0.2 * texture_a(north, east)) * a + (1.0 + 0.2 * texture_b(north, east)) * b)
      .cast<float>();
}

EnviHeader header(int rows, int cols, const EnviMapInfo& map) {
  EnviHeader out;
  out.samples = cols;
  out.lines = rows;
  out.bands = kBands;
  out.data_type = EnviDataType::float32;
  out.interleave = EnviInterleave::bil;
  out.map_info = map;
  return out;
}

// truth/reflectance.hdr over the fixture's footprint, textured.
void writeTexturedTruth(const EvaluationFixture& fixture) {
  EnviMapInfo map;
  map.projection = "Arbitrary";
  map.easting = kTruthEastMin;
  map.northing = kTruthNorthMax;
  map.pixel_size_x = map.pixel_size_y = kTruthPixel;
  map.units = "Meters";
  EnviWriter writer(fixture.truth() / "reflectance.hdr", header(kTruthSide, kTruthSide, map));
  Eigen::MatrixXf line(kBands, kTruthSide);
  for (int r = 0; r < kTruthSide; ++r) {
    for (int c = 0; c < kTruthSide; ++c) {
      const bool valid = c >= kTruthNanColumns && c < kTruthSide - kTruthNanColumns;
      line.col(c) = valid ? seabed(kTruthNorthMax - (r + 0.5) * kTruthPixel,
                                   kTruthEastMin + (c + 0.5) * kTruthPixel)
                          : Eigen::VectorXf::Constant(kBands, kNaN);
    }
    writer.writeLine(line);
  }
  writer.finish();
}

// RUN/hyperspectral/ortho.hdr: north-up in the origin's UTM zone at 4 mm,
// over the truth raster's UTM bounding box plus 5 cm; its pixel at W
// position (north, east) shows the seabed at (north, east) - shift_NE.
void writeOrtho(const EvaluationFixture& fixture, const Eigen::Vector2d& shift_NE) {
  const UtmProjection utm(*fixture.config().origin);
  double e_min = 1e300, e_max = -1e300, n_min = 1e300, n_max = -1e300;
  for (const double north : {kTruthNorthMax - kTruthSide * kTruthPixel, kTruthNorthMax}) {
    for (const double east : {kTruthEastMin, kTruthEastMin + kTruthSide * kTruthPixel}) {
      const Eigen::Vector2d en = utm.nedToUtm(Eigen::Vector3d(north, east, 0.0));
      e_min = std::min(e_min, en.x());
      e_max = std::max(e_max, en.x());
      n_min = std::min(n_min, en.y());
      n_max = std::max(n_max, en.y());
    }
  }
  constexpr double kMargin = 0.05;
  EnviMapInfo map;
  map.projection = "UTM";
  map.easting = e_min - kMargin;
  map.northing = n_max + kMargin;
  map.pixel_size_x = map.pixel_size_y = kOrthoPixel;
  map.zone = utm.zone();
  map.north = utm.northernHemisphere();
  map.datum = "WGS-84";
  map.units = "Meters";
  const int cols = static_cast<int>(std::ceil((e_max - e_min + 2 * kMargin) / kOrthoPixel));
  const int rows = static_cast<int>(std::ceil((n_max - n_min + 2 * kMargin) / kOrthoPixel));
  const std::filesystem::path hdr = fixture.run() / results_paths::ortho_hdr;
  std::filesystem::create_directories(hdr.parent_path());
  EnviWriter writer(hdr, header(rows, cols, map));
  Eigen::MatrixXf line(kBands, cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector3d p_W = utm.utmToNed(map.easting + (c + 0.5) * kOrthoPixel,
                                               map.northing - (r + 0.5) * kOrthoPixel, 0.0);
      line.col(c) = seabed(p_W.x() - shift_NE.x(), p_W.y() - shift_NE.y());
    }
    writer.writeLine(line);
  }
  writer.finish();
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A number of metrics.json by key; NaN when absent or null.
double jsonNumber(const std::string& json, const std::string& key) {
  const std::regex pattern("\"" + key + "\": (null|[-0-9.eE+]+)");
  std::smatch match;
  if (!std::regex_search(json, match, pattern) || match[1] == "null") return std::nan("");
  return std::stod(match[1]);
}

class EvaluateOrthoTest : public ::testing::Test {
 protected:
  EvaluationFixture fixture_;
};

TEST_F(EvaluateOrthoTest, AnOrthoImageInTheRunIsMeasuredIntoMetricsJson) {
  fixture_.writeRunEqualToTruth();
  writeTexturedTruth(fixture_);
  const Eigen::Vector2d shift_NE(0.0, 0.02);  // the product placed 2 cm east
  writeOrtho(fixture_, shift_NE);
  const EvaluationReport report = evaluateRunFolder(fixture_.run(), fixture_.truth());
  std::ostringstream table;
  printMetricsTable(table, report.metrics);
  std::cout << table.str();

  const std::string json = readText(report.metrics_path);
  // The shift is the geo-referencing error; the map is undistorted. The
  // bounds are ortho_metrics_test.cc's: at these resolutions and with as
  // many patches (24) its noise floor (ortho_metrics.h) is ~0.5 mm of
  // registration rmse, the mean shift within ~0.3 mm, the scale within ~3e-4.
  EXPECT_NEAR(jsonNumber(json, "ortho_mean_shift_m"), shift_NE.norm(), 0.002) << json;
  EXPECT_LT(jsonNumber(json, "ortho_registration_rmse_m"), 0.001) << json;
  EXPECT_LT(jsonNumber(json, "ortho_scale_error"), 0.001) << json;
  // Compared at the registered position, the spectra agree (nearest pixels
  // up to 2.8 mm apart in a texture of 1 cm: a fraction of a degree).
  EXPECT_LT(jsonNumber(json, "ortho_sam_deg"), 0.5) << json;
  // The product covers the whole footprint.
  EXPECT_EQ(jsonNumber(json, "ortho_coverage"), 1.0) << json;
  // The patch counts go in the table: 0.3 m patches are 60 pixels; 6 x 6
  // tile the raster, the 12 over the NaN columns have no data; nearly all
  // the others match.
  EXPECT_NE(table.str().find("  ortho: 36 patches of 60 px, 24 with data, "), std::string::npos)
      << table.str();
  const std::regex matched("24 with data, ([0-9]+) matched");
  std::smatch match;
  const std::string text = table.str();
  ASSERT_TRUE(std::regex_search(text, match, matched)) << text;
  EXPECT_GE(std::stoi(match[1]), 20) << text;
}

TEST_F(EvaluateOrthoTest, WithoutAnOrthoImageTheFiveAreNullAndSayWhy) {
  fixture_.writeRunEqualToTruth();
  const EvaluationReport report = evaluateRunFolder(fixture_.run(), fixture_.truth());
  for (const MetricValue* metric :
       {&report.metrics.ortho_mean_shift_m, &report.metrics.ortho_registration_rmse_m,
        &report.metrics.ortho_scale_error, &report.metrics.ortho_sam_deg,
        &report.metrics.ortho_coverage}) {
    EXPECT_FALSE(metric->value.has_value());
    EXPECT_EQ(metric->reason, kNoOrthoImage);
  }
  EXPECT_TRUE(report.metrics.ortho_patches.empty());
  EXPECT_NE(readText(report.metrics_path).find("\"ortho_coverage\": null"), std::string::npos);
}

TEST_F(EvaluateOrthoTest, AnOrthoImageWithoutTheTrueOneIsAnInputErrorNamingIt) {
  fixture_.writeRunEqualToTruth();
  writeOrtho(fixture_, Eigen::Vector2d::Zero());
  const std::filesystem::path truth_hdr = fixture_.truth() / "reflectance.hdr";
  std::filesystem::remove(truth_hdr);
  try {
    measureRunOrtho(fixture_.run() / results_paths::ortho_hdr, truth_hdr,
                    *fixture_.config().origin);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), truth_hdr);
    EXPECT_NE(std::string(e.what()).find("reflectance.hdr"), std::string::npos) << e.what();
  }
  // Through the command, the truth's loading already names it.
  try {
    evaluateRunFolder(fixture_.run(), fixture_.truth());
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), truth_hdr);
  }
}

}  // namespace
}  // namespace hsmap
