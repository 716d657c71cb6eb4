// measureOrtho (ortho_metrics.h) on synthetic rasters: a smooth random
// texture defined continuously in W, sampled on a truth grid in W (5 mm) and,
// through UtmProjection, on a produced grid in UTM (4 mm, rotated from W by
// the meridian convergence, ~1.4 degrees at the origin used), with known
// distortions between the two.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "core/geometry/utm_projection.h"
#include "core/io/envi_header.h"
#include "core/io/envi_writer.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "tests/pipelines/evaluate/smooth_texture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::TempFolder;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kBands = 4;

// The truth raster: 1.2 m (north) x 2.0 m (east) at 5 mm, upper-left corner at
// north 1.2, east 0.
constexpr double kTruthPixel = 0.005;
constexpr int kTruthRows = 240, kTruthCols = 400;
constexpr double kTruthNorthMax = 1.2, kTruthEastMin = 0.0;
constexpr double kProducedPixel = 0.004;
// What "registration rmse ~0" means here: 0.2 pixel of the truth (see
// IdenticalProductScoresZero).
constexpr double kRmseFloor = 0.001;

GeodeticPoint surveyOrigin() { return GeodeticPoint{43.0, 5.0, 0.0}; }

// The textures, over north -0.5..2.0 m, east -0.5..2.75 m.
using Texture = testing::SmoothTexture;
Texture makeTexture(unsigned seed) { return Texture(seed, -0.5, -0.5, 1000, 1300); }

const Texture& texture1() {
  static const Texture texture = makeTexture(11);
  return texture;
}
const Texture& texture2() {
  static const Texture texture = makeTexture(23);
  return texture;
}

Eigen::VectorXd spectrum1() { return Eigen::Vector4d(0.2, 0.4, 0.6, 0.3); }
Eigen::VectorXd spectrum2() { return Eigen::Vector4d(0.5, 0.3, 0.1, 0.4); }

// Two materials mixed by two textures: the spectrum's direction varies.
Eigen::VectorXd mixedSeabed(const Eigen::Vector2d& ne) {
  return (1.0 + 0.2 * texture1()(ne.x(), ne.y())) * spectrum1() + (1.0 + 0.2 * texture2()(ne.x(), ne.y())) * spectrum2();
}
// One material, its brightness textured: the spectrum's direction is constant.
Eigen::VectorXd singleMaterial(const Eigen::Vector2d& ne) {
  return (1.0 + 0.2 * texture1()(ne.x(), ne.y())) * spectrum1();
}

using Spectrum = std::function<std::optional<Eigen::VectorXd>(const Eigen::Vector2d& ne)>;

EnviHeader rasterHeader(int rows, int cols, const EnviMapInfo& map) {
  EnviHeader header;
  header.samples = cols;
  header.lines = rows;
  header.bands = kBands;
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.map_info = map;
  return header;
}

// Writes a raster whose pixel (r, c) has the spectrum at position_NE(r, c)
// (NaN, or `ignore` when given, where `spectrum` has none).
void writeRaster(const std::filesystem::path& hdr, EnviHeader header,
                 const std::function<Eigen::Vector2d(int, int)>& position_NE, const Spectrum& spectrum,
                 std::optional<float> ignore = std::nullopt) {
  if (ignore) header.other_fields.emplace_back("data ignore value", std::to_string(*ignore));
  EnviWriter writer(hdr, header);
  Eigen::MatrixXf line(header.bands, header.samples);
  for (int r = 0; r < header.lines; ++r) {
    for (int c = 0; c < header.samples; ++c) {
      const std::optional<Eigen::VectorXd> value = spectrum(position_NE(r, c));
      if (value) {
        line.col(c) = value->cast<float>();
      } else {
        line.col(c).setConstant(ignore ? *ignore : kNaN);
      }
    }
    writer.writeLine(line);
  }
  writer.finish();
}

void writeTruth(const std::filesystem::path& hdr, const Spectrum& spectrum) {
  EnviMapInfo map;
  map.projection = "Arbitrary";
  map.easting = kTruthEastMin;
  map.northing = kTruthNorthMax;
  map.pixel_size_x = map.pixel_size_y = kTruthPixel;
  map.units = "Meters";
  writeRaster(
      hdr, rasterHeader(kTruthRows, kTruthCols, map),
      [](int r, int c) {
        return Eigen::Vector2d(kTruthNorthMax - (r + 0.5) * kTruthPixel,
                               kTruthEastMin + (c + 0.5) * kTruthPixel);
      },
      spectrum);
}

// The produced grid: the UTM bounding box of the truth raster plus 5 cm, at
// 4 mm; the W position of every pixel centre, computed once.
struct ProducedGrid {
  EnviMapInfo map;
  int rows = 0, cols = 0;
  std::vector<Eigen::Vector2d> centres_NE;
};

const ProducedGrid& producedGrid() {
  static const ProducedGrid grid = [] {
    const UtmProjection utm(surveyOrigin());
    double e_min = 1e300, e_max = -1e300, n_min = 1e300, n_max = -1e300;
    for (const double north : {kTruthNorthMax - kTruthRows * kTruthPixel, kTruthNorthMax}) {
      for (const double east : {kTruthEastMin, kTruthEastMin + kTruthCols * kTruthPixel}) {
        const Eigen::Vector2d en = utm.nedToUtm(Eigen::Vector3d(north, east, 0.0));
        e_min = std::min(e_min, en.x());
        e_max = std::max(e_max, en.x());
        n_min = std::min(n_min, en.y());
        n_max = std::max(n_max, en.y());
      }
    }
    ProducedGrid out;
    constexpr double kMargin = 0.05;
    out.map.projection = "UTM";
    out.map.easting = e_min - kMargin;
    out.map.northing = n_max + kMargin;
    out.map.pixel_size_x = out.map.pixel_size_y = kProducedPixel;
    out.map.zone = utm.zone();
    out.map.north = utm.northernHemisphere();
    out.map.datum = "WGS-84";
    out.map.units = "Meters";
    out.cols = static_cast<int>(std::ceil((e_max - e_min + 2 * kMargin) / kProducedPixel));
    out.rows = static_cast<int>(std::ceil((n_max - n_min + 2 * kMargin) / kProducedPixel));
    out.centres_NE.reserve(static_cast<std::size_t>(out.rows) * out.cols);
    for (int r = 0; r < out.rows; ++r) {
      for (int c = 0; c < out.cols; ++c) {
        const Eigen::Vector3d p_W = utm.utmToNed(out.map.easting + (c + 0.5) * kProducedPixel,
                                                 out.map.northing - (r + 0.5) * kProducedPixel, 0.0);
        out.centres_NE.emplace_back(p_W.x(), p_W.y());
      }
    }
    return out;
  }();
  return grid;
}

// Writes the produced raster: its pixel at W position y shows spectrum(y).
void writeProduced(const std::filesystem::path& hdr, const Spectrum& spectrum,
                   std::optional<float> ignore = std::nullopt) {
  const ProducedGrid& grid = producedGrid();
  writeRaster(
      hdr, rasterHeader(grid.rows, grid.cols, grid.map),
      [&](int r, int c) { return grid.centres_NE[static_cast<std::size_t>(r) * grid.cols + c]; },
      spectrum, ignore);
}

// The product showing at y the true content of source(y): that content is
// displaced from source(y) to y.
Spectrum warped(Spectrum spectrum, std::function<Eigen::Vector2d(const Eigen::Vector2d&)> source) {
  return [spectrum, source](const Eigen::Vector2d& y) { return spectrum(source(y)); };
}

struct Rasters {
  TempFolder temp;
  std::filesystem::path truth = temp / "reflectance.hdr";
  std::filesystem::path produced = temp / "ortho.hdr";
};

Spectrum always(Eigen::VectorXd (*f)(const Eigen::Vector2d&)) {
  return [f](const Eigen::Vector2d& ne) { return std::optional<Eigen::VectorXd>(f(ne)); };
}

OrthoMetrics measure(const Rasters& rasters) {
  const OrthoMetrics metrics = measureOrtho(rasters.produced, rasters.truth, surveyOrigin());
  std::cout << metrics.summary();
  if (std::getenv("ORTHO_DEBUG")) {
    for (const auto& m : metrics.matches) {
      std::cout << "  match " << m.centre_NE.transpose() << " d " << 1000 * m.displacement_NE.transpose()
                << " mm r " << m.response << "\n";
    }
  }
  return metrics;
}

TEST(OrthoMetrics, IdenticalProductScoresZero) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  writeProduced(rasters.produced, always(mixedSeabed));
  const OrthoMetrics metrics = measure(rasters);
  EXPECT_EQ(metrics.patch_pixels, 60);  // 0.3 m at 5 mm
  EXPECT_EQ(metrics.patches, 4 * 6);
  EXPECT_EQ(metrics.patches_with_data, metrics.patches);
  EXPECT_GE(metrics.patches_matched, 0.9 * metrics.patches);
  ASSERT_TRUE(metrics.ortho_mean_shift_m.value);
  EXPECT_LT(*metrics.ortho_mean_shift_m.value, 0.0005);
  // The noise floor of one patch's displacement: ~0.1 pixel (0.5 mm), from
  // the interpolation differences that phase correlation's whitening
  // amplifies at high frequencies (ortho_metrics.h).
  EXPECT_LT(*metrics.ortho_registration_rmse_m.value, kRmseFloor);
  EXPECT_LT(*metrics.ortho_scale_error.value, 0.001);
  // Nearest-pixel spectra of a texture whose spectral direction varies: the
  // produced pixel is up to 2.8 mm from the truth pixel's centre.
  EXPECT_LT(*metrics.ortho_sam_deg.value, 0.5);
  EXPECT_EQ(metrics.sam_pixels, kTruthRows * kTruthCols);
  EXPECT_DOUBLE_EQ(*metrics.ortho_coverage.value, 1.0);
  EXPECT_EQ(metrics.footprint_pixels, kTruthRows * kTruthCols);
}

TEST(OrthoMetrics, KnownShiftIsTheMeanShift) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  const Eigen::Vector2d d_NE(0.01, 0.03);  // 1 cm north, 3 cm east
  writeProduced(rasters.produced,
                warped(always(mixedSeabed), [&](const Eigen::Vector2d& y) { return Eigen::Vector2d(y - d_NE); }));
  const OrthoMetrics metrics = measure(rasters);
  EXPECT_GE(metrics.patches_matched, 0.9 * metrics.patches);
  ASSERT_TRUE(metrics.ortho_mean_shift_m.value);
  EXPECT_NEAR(*metrics.ortho_mean_shift_m.value, d_NE.norm(), 0.002);
  for (const OrthoPatchMatch& match : metrics.matches) {
    EXPECT_LT((match.displacement_NE - d_NE).norm(), 0.003) << match.centre_NE.transpose();
  }
  EXPECT_LT(*metrics.ortho_registration_rmse_m.value, kRmseFloor);
  EXPECT_LT(*metrics.ortho_scale_error.value, 0.001);
  // Compared at the registered position, the spectra agree again.
  EXPECT_TRUE(metrics.sam_registered);
  EXPECT_LT(*metrics.ortho_sam_deg.value, 0.5);
  EXPECT_DOUBLE_EQ(*metrics.ortho_coverage.value, 1.0);
}

TEST(OrthoMetrics, ShiftLargerThanHalfAPatchIsFoundByTheCoarseStage) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  const Eigen::Vector2d d_NE(-0.05, 0.2);  // 20 cm east: beyond a 0.3 m patch's +-0.15 m
  writeProduced(rasters.produced,
                warped(always(mixedSeabed), [&](const Eigen::Vector2d& y) { return Eigen::Vector2d(y - d_NE); }));
  const OrthoMetrics metrics = measure(rasters);
  ASSERT_TRUE(metrics.coarse_shift_NE);
  ASSERT_TRUE(metrics.ortho_mean_shift_m.value) << metrics.ortho_mean_shift_m.reason;
  EXPECT_NEAR(*metrics.ortho_mean_shift_m.value, d_NE.norm(), 0.002);
  EXPECT_LT(*metrics.ortho_registration_rmse_m.value, kRmseFloor);
}

TEST(OrthoMetrics, ScaledProductGivesItsScaleError) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  // The product is the truth scaled by 1.01 about c: true content at x is shown at c + 1.01 (x - c).
  const Eigen::Vector2d c_NE(0.6, 1.0);
  writeProduced(rasters.produced,
                warped(always(mixedSeabed),
                       [&](const Eigen::Vector2d& y) { return Eigen::Vector2d(c_NE + (y - c_NE) / 1.01); }));
  const OrthoMetrics metrics = measure(rasters);
  ASSERT_TRUE(metrics.ortho_scale_error.value) << metrics.ortho_scale_error.reason;
  EXPECT_NEAR(*metrics.ortho_scale_error.value, 0.01, 0.001);
  EXPECT_LT(*metrics.ortho_registration_rmse_m.value, kRmseFloor);
  EXPECT_NEAR(*metrics.rotation_deg, 0.0, 0.1);
}

TEST(OrthoMetrics, LocalWarpLeavesItsResidual) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  // One region (Gaussian, sigma 0.25 m, around c) displaced by up to 1.5 cm east.
  const Eigen::Vector2d c_NE(0.8, 0.6), a_NE(0.0, 0.015);
  constexpr double kSigma = 0.25;
  const auto bump = [&](const Eigen::Vector2d& x) {
    return std::exp(-(x - c_NE).squaredNorm() / (2 * kSigma * kSigma));
  };
  writeProduced(rasters.produced,
                warped(always(mixedSeabed),
                       [&](const Eigen::Vector2d& y) { return Eigen::Vector2d(y - a_NE * bump(y)); }));
  const OrthoMetrics metrics = measure(rasters);
  ASSERT_TRUE(metrics.ortho_registration_rmse_m.value) << metrics.ortho_registration_rmse_m.reason;
  // A displacement smoother than a patch is found again on the shifted windows.
  EXPECT_EQ(metrics.patches_unconfirmed, 0);

  // The expected residual: the displacement field at the matched centres
  // (x + a bump(x), to first order), less its own best similarity.
  double sum_ad = 0, sum_cross = 0, sum_aa = 0;
  std::vector<Eigen::Vector2d> a, b;
  for (const OrthoPatchMatch& match : metrics.matches) {
    EXPECT_LT((match.displacement_NE - a_NE * bump(match.centre_NE)).norm(), 0.0025)
        << match.centre_NE.transpose();
    a.push_back(match.centre_NE);
    b.push_back(match.centre_NE + a_NE * bump(match.centre_NE));
  }
  Eigen::Vector2d mean_a = Eigen::Vector2d::Zero(), mean_b = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    mean_a += a[i];
    mean_b += b[i];
  }
  mean_a /= a.size();
  mean_b /= b.size();
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector2d u = a[i] - mean_a, v = b[i] - mean_b;
    sum_ad += u.dot(v);
    sum_cross += u.x() * v.y() - u.y() * v.x();
    sum_aa += u.squaredNorm();
  }
  Eigen::Matrix2d M;
  M << sum_ad / sum_aa, -sum_cross / sum_aa, sum_cross / sum_aa, sum_ad / sum_aa;
  double sum2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sum2 += (b[i] - (M * (a[i] - mean_a) + mean_b)).squaredNorm();
  }
  const double expected_rmse = std::sqrt(sum2 / a.size());
  std::cout << "expected registration rmse " << expected_rmse << " m\n";
  EXPECT_GT(expected_rmse, 0.002);
  EXPECT_NEAR(*metrics.ortho_registration_rmse_m.value, expected_rmse, 0.3 * expected_rmse);
}

TEST(OrthoMetrics, HalfEmptyProductCoversHalf) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  // Empty east of the truth's middle (east 1.0 m), written as the header's data ignore value.
  writeProduced(
      rasters.produced,
      [](const Eigen::Vector2d& y) -> std::optional<Eigen::VectorXd> {
        if (y.y() > 1.0) return std::nullopt;
        return mixedSeabed(y);
      },
      -9999.0f);
  const OrthoMetrics metrics = measure(rasters);
  ASSERT_TRUE(metrics.ortho_coverage.value);
  EXPECT_NEAR(*metrics.ortho_coverage.value, 0.5, 0.005);
  EXPECT_EQ(metrics.patches_with_data, metrics.patches / 2);
  EXPECT_GE(metrics.patches_matched, 0.9 * metrics.patches_with_data);
  ASSERT_TRUE(metrics.ortho_mean_shift_m.value);
  EXPECT_LT(*metrics.ortho_mean_shift_m.value, 0.0005);
  // The spectral angle is over covered pixels only.
  EXPECT_NEAR(static_cast<double>(metrics.sam_pixels) / metrics.footprint_pixels, 0.5, 0.005);
  EXPECT_LT(*metrics.ortho_sam_deg.value, 0.5);
}

TEST(OrthoMetrics, SpectralAngleIgnoresBrightnessAndMeasuresAKnownAngle) {
  Rasters rasters;
  writeTruth(rasters.truth, always(singleMaterial));
  // Scaled by a constant (e.g. uncorrected gain): angle 0.
  writeProduced(
      rasters.produced,
      [](const Eigen::Vector2d& y) { return std::optional<Eigen::VectorXd>(2.5 * singleMaterial(y)); });
  OrthoMetrics metrics = measure(rasters);
  ASSERT_TRUE(metrics.ortho_sam_deg.value);
  EXPECT_LT(*metrics.ortho_sam_deg.value, 0.01);
  EXPECT_GE(metrics.patches_matched, 0.9 * metrics.patches);  // the band mean is only scaled

  // Turned by 10 degrees towards a direction orthogonal to the material's.
  constexpr double kAngleDeg = 10.0;
  const Eigen::VectorXd s = spectrum1().normalized();
  Eigen::VectorXd other = Eigen::Vector4d(1.0, -1.0, 0.5, 0.2);
  other = (other - other.dot(s) * s).normalized();
  const double theta = kAngleDeg * std::numbers::pi / 180.0;
  const Eigen::VectorXd turned = std::cos(theta) * s + std::sin(theta) * other;
  writeProduced(
      rasters.produced,
      [&](const Eigen::Vector2d& y) {
        return std::optional<Eigen::VectorXd>(singleMaterial(y).norm() * turned);
      });
  metrics = measure(rasters);
  ASSERT_TRUE(metrics.ortho_sam_deg.value);
  EXPECT_NEAR(*metrics.ortho_sam_deg.value, kAngleDeg, 0.01);
  EXPECT_EQ(metrics.sam_stride, 1);

  // On a lattice (stride 4 for 6000 pixels), streamed in chunks of a few lines.
  OrthoMetricsOptions options;
  options.max_sam_pixels = 6000;
  options.sam_chunk_bytes = 2000;
  metrics = measureOrtho(rasters.produced, rasters.truth, surveyOrigin(), options);
  EXPECT_EQ(metrics.sam_stride, 4);
  EXPECT_EQ(metrics.sam_pixels, (kTruthRows / 4) * (kTruthCols / 4));
  ASSERT_TRUE(metrics.ortho_sam_deg.value);
  EXPECT_NEAR(*metrics.ortho_sam_deg.value, kAngleDeg, 0.01);
}

TEST(OrthoMetrics, FeaturelessProductCannotBeRegistered) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  writeProduced(
      rasters.produced,
      [](const Eigen::Vector2d&) { return std::optional<Eigen::VectorXd>(Eigen::Vector4d::Constant(0.5)); });
  const OrthoMetrics metrics = measure(rasters);
  EXPECT_EQ(metrics.patches_with_data, metrics.patches);
  EXPECT_EQ(metrics.patches_matched, 0);
  for (const MetricValue* value :
       {&metrics.ortho_mean_shift_m, &metrics.ortho_registration_rmse_m, &metrics.ortho_scale_error}) {
    EXPECT_FALSE(value->value);
    EXPECT_NE(value->reason.find("too few patches match: 0 of 24"), std::string::npos) << value->reason;
  }
  EXPECT_DOUBLE_EQ(*metrics.ortho_coverage.value, 1.0);
  EXPECT_FALSE(metrics.sam_registered);
}

TEST(OrthoMetrics, UnrelatedProductCannotBeRegistered) {
  Rasters rasters;
  writeTruth(rasters.truth, always(singleMaterial));
  // Another texture entirely: correlations are not confident.
  writeProduced(
      rasters.produced,
      [](const Eigen::Vector2d& y) {
        return std::optional<Eigen::VectorXd>((1.0 + 0.2 * texture2()(y.x(), y.y())) * spectrum1());
      });
  const OrthoMetrics metrics = measure(rasters);
  EXPECT_EQ(metrics.patches_with_data, metrics.patches);
  EXPECT_LT(metrics.patches_matched, 0.3 * metrics.patches);
  EXPECT_FALSE(metrics.ortho_mean_shift_m.value);
}

// Content displaced over less than a patch, at a patch's centre (a square
// of 0.2 m moved 6 cm east; the rest exact): the Hanning window weighs the
// centre most, so that patch alone "matches" at the square's displacement,
// which is not a displacement of the map at the scale the metric measures.
// On the window shifted by a quarter patch the square is off-centre and the
// match lands elsewhere: not confirmed. Without the confirmation, this one
// patch would dominate the registration error.
TEST(OrthoMetrics, ADisplacementSmallerThanAPatchIsNotConfirmed) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  // Patch (row 1, column 2) of the 4 x 6 tiling spans rows 60-119 and columns
  // 140-199 of the truth: centre north 0.75 m, east 0.85 m.
  const Eigen::Vector2d centre_NE(0.75, 0.85), shift_NE(0.0, 0.06);
  writeProduced(rasters.produced, warped(always(mixedSeabed), [&](const Eigen::Vector2d& y) {
                  const bool inside = (y - centre_NE).cwiseAbs().maxCoeff() < 0.1;
                  return Eigen::Vector2d(inside ? y - shift_NE : y);
                }));
  OrthoMetricsOptions unconfirmed;
  unconfirmed.confirm_matches = false;
  const OrthoMetrics without = measureOrtho(rasters.produced, rasters.truth, surveyOrigin(), unconfirmed);
  std::cout << without.summary();
  ASSERT_TRUE(without.ortho_registration_rmse_m.value);
  EXPECT_GT(*without.ortho_registration_rmse_m.value, 0.005);

  const OrthoMetrics with = measure(rasters);
  ASSERT_TRUE(with.ortho_registration_rmse_m.value);
  EXPECT_EQ(with.patches_unconfirmed, 1);
  EXPECT_EQ(with.patches_matched, without.patches_matched - 1);
  EXPECT_LT(*with.ortho_registration_rmse_m.value, kRmseFloor);
  for (const OrthoPatchMatch& match : with.matches) {
    EXPECT_GT((match.centre_NE - centre_NE).norm(), 0.1) << "the displaced patch was kept";
  }
}

// A 2-D similarity of W (north, east): content at x lies at c + s R (x - c) + t,
// R turning (north, east) by theta.
struct KnownSimilarity {
  double scale = 1.0, theta_deg = 0.0;
  Eigen::Vector2d centre_NE = Eigen::Vector2d::Zero(), shift_NE = Eigen::Vector2d::Zero();

  Eigen::Matrix2d rotation() const {
    const double th = theta_deg * std::numbers::pi / 180.0;
    return (Eigen::Matrix2d() << std::cos(th), -std::sin(th), std::sin(th), std::cos(th)).finished();
  }
  Eigen::Vector2d apply(const Eigen::Vector2d& x) const {
    return centre_NE + scale * rotation() * (x - centre_NE) + shift_NE;
  }
  Eigen::Vector2d inverse(const Eigen::Vector2d& y) const {
    return centre_NE + rotation().transpose() * (y - centre_NE - shift_NE) / scale;
  }
};

// A map scale error far beyond what a whole-image shift can start the patches
// from (ortho_metrics.h, step 2): at 15 % the patches 1 m from the scale's
// centre are displaced by 15 cm and their content stretched by 4.5 cm. With
// the coarse similarity every patch is matched, and the figures are those of
// the similarity itself: its scale, a registration error of ~0, and each
// patch's displacement S(a) - a.
TEST(OrthoMetrics, LargeScaleErrorAndRotationAreRegistered) {
  for (const double scale : {1.15, 0.87}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    Rasters rasters;
    writeTruth(rasters.truth, always(mixedSeabed));
    KnownSimilarity S;
    S.scale = scale;
    S.theta_deg = 3.0;
    S.centre_NE = Eigen::Vector2d(0.35, 1.4);  // off the truth's centre (0.6, 1.0)
    S.shift_NE = Eigen::Vector2d(0.03, -0.05);
    writeProduced(rasters.produced,
                  warped(always(mixedSeabed), [&](const Eigen::Vector2d& y) { return S.inverse(y); }));
    const OrthoMetrics metrics = measure(rasters);
    ASSERT_TRUE(metrics.ortho_registration_rmse_m.value) << metrics.ortho_registration_rmse_m.reason;
    ASSERT_TRUE(metrics.coarse_scale);
    EXPECT_NEAR(*metrics.coarse_scale, scale, 0.02);
    EXPECT_GE(metrics.patches_matched, 0.9 * metrics.patches_with_data);
    EXPECT_NEAR(*metrics.ortho_scale_error.value, std::abs(scale - 1.0), 0.005);
    EXPECT_LT(*metrics.ortho_registration_rmse_m.value, kRmseFloor);
    ASSERT_TRUE(metrics.rotation_deg);
    EXPECT_NEAR(std::abs(*metrics.rotation_deg), 3.0, 0.05);
    Eigen::Vector2d mean_d = Eigen::Vector2d::Zero();
    for (const OrthoPatchMatch& match : metrics.matches) {
      const Eigen::Vector2d expected = S.apply(match.centre_NE) - match.centre_NE;
      EXPECT_LT((match.displacement_NE - expected).norm(), 0.003) << match.centre_NE.transpose();
      mean_d += expected;
    }
    mean_d /= static_cast<double>(metrics.matches.size());
    EXPECT_NEAR(*metrics.ortho_mean_shift_m.value, mean_d.norm(), 0.002);
    // Spectra and coverage at the registered position.
    EXPECT_TRUE(metrics.sam_registered);
    EXPECT_LT(*metrics.ortho_sam_deg.value, 0.5);
  }
}

// The coarse similarity only starts the patches: a map's local distortion is
// measured through an 11 % scale as it is without one. The distortion w is
// the map's own (in map metres): content at x lies at z + w(z), z = S(x),
// against x + w(x) without the scale. (Had the distortion been scaled with
// the map, content at S(x + w(x)), its residual would be s |w|:
// ortho_registration_rmse_m is in the produced map's metres.) w turns
// through a plane wave of ~0.6 m with a constant length of 4 mm, so that its
// RMS does not depend on where the patches sample it (with and without the
// scale they sample it at different places).
TEST(OrthoMetrics, LocalDistortionIsMeasuredThroughALargeScaleError) {
  constexpr double kAmplitude = 0.004;
  const auto wobble = [](const Eigen::Vector2d& z) {
    const double phase = 2 * std::numbers::pi * (z.x() / 0.8 + z.y() / 1.0);
    return Eigen::Vector2d(kAmplitude * std::sin(phase), kAmplitude * std::cos(phase));
  };
  // y = z + w(z) solved for z (w is a contraction: |grad w| ~ 0.03).
  const auto unwobble = [&](const Eigen::Vector2d& y) {
    Eigen::Vector2d z = y;
    for (int i = 0; i < 6; ++i) z = y - wobble(z);
    return z;
  };
  KnownSimilarity S;
  S.scale = 1.11;
  S.centre_NE = Eigen::Vector2d(0.6, 1.0);
  S.shift_NE = Eigen::Vector2d(-0.02, 0.04);

  Rasters distorted;
  writeTruth(distorted.truth, always(mixedSeabed));
  writeProduced(distorted.produced, warped(always(mixedSeabed), unwobble));
  const OrthoMetrics without_scale = measure(distorted);

  Rasters scaled;
  writeTruth(scaled.truth, always(mixedSeabed));
  writeProduced(scaled.produced, warped(always(mixedSeabed),
                                        [&](const Eigen::Vector2d& y) { return S.inverse(unwobble(y)); }));
  const OrthoMetrics with_scale = measure(scaled);

  ASSERT_TRUE(without_scale.ortho_registration_rmse_m.value) << without_scale.ortho_registration_rmse_m.reason;
  ASSERT_TRUE(with_scale.ortho_registration_rmse_m.value) << with_scale.ortho_registration_rmse_m.reason;
  const double reference = *without_scale.ortho_registration_rmse_m.value;
  // Well above the metric's noise (kRmseFloor), so that 10 % means something.
  EXPECT_GT(reference, 0.002);
  EXPECT_NEAR(*with_scale.ortho_registration_rmse_m.value, reference, 0.1 * reference);
  EXPECT_NEAR(*with_scale.ortho_scale_error.value, 0.11, 0.005);
  EXPECT_LT(*without_scale.ortho_scale_error.value, 0.005);
}

TEST(OrthoMetrics, ProducedRasterInAnotherZoneIsAnInputError) {
  Rasters rasters;
  writeTruth(rasters.truth, always(mixedSeabed));
  writeProduced(rasters.produced, always(mixedSeabed));
  EnviHeader header = readEnviHeader(rasters.produced);
  header.map_info->zone += 1;
  writeEnviHeader(rasters.produced, header);
  EXPECT_THROW(measureOrtho(rasters.produced, rasters.truth, surveyOrigin()), InputError);
  header.map_info->zone -= 1;
  writeEnviHeader(rasters.produced, header);
  // The truth must be in local W.
  EnviHeader truth_header = readEnviHeader(rasters.truth);
  truth_header.map_info = header.map_info;
  writeEnviHeader(rasters.truth, truth_header);
  EXPECT_THROW(measureOrtho(rasters.produced, rasters.truth, surveyOrigin()), InputError);
}

}  // namespace
}  // namespace hsmap
