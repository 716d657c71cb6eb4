// The matching-free ortho pixel error (ortho_pixel_error.h) on the
// evaluation fixture's survey (evaluation_fixture.h: 90 true scan lines over
// a flat seabed 22 m down, the sample's 64-sample UHI camera), with
// hand-made ancillary layers on a UTM grid of 1 cm pixels over W's north
// [0.8, 1.6] x east [-0.2, 0.2] m, inside the swath. Patches of 0.2 m (20
// pixels) tile it exactly: 4 rows by 2 columns of patches.
//
// Each pixel's ancillary line and sample are found by inverting the true
// geometry: the (fractional) line whose interpolated pose sees the target
// point in its plane (y_U = 0, by bisection) and the sample it projects to.
// With the target the pixel's own centre the layer is truth-consistent;
// with the centre minus a displacement d(p), every pixel lands d(p) off.
#include "pipelines/evaluate/ortho_pixel_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "core/geometry/pose_interpolation.h"
#include "core/geometry/utm_projection.h"
#include "core/io/envi_writer.h"
#include "core/io/results_folder.h"
#include "core/util/input_error.h"
#include "pipelines/evaluate/ortho_metrics.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;

constexpr double kPixel = 0.01;
constexpr double kNorthMax = 1.6, kEastMin = -0.2;
constexpr int kRows = 80, kCols = 40;
constexpr double kPatch = 0.2;  // 20 pixels: 4 x 2 patches
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Displacement (north, east) of the pixel at (row, col): where its content
// lies on the map minus where it truly lies.
using Displacement = std::function<Eigen::Vector2d(int row, int col)>;

// The fractional line and the sample that truly see p_W; nullopt when no
// line does.
std::optional<Eigen::Vector2d> lineAndSample(const Eigen::Vector3d& p_W, const std::vector<SE3d>& T_W_U,
                                             const PushbroomCamera& camera) {
  const auto across = [&](const SE3d& T) {
    const Eigen::Vector3d p_U = T.inverse() * p_W;
    return p_U.y() / p_U.z();
  };
  for (std::size_t k = 0; k + 1 < T_W_U.size(); ++k) {
    const double a = across(T_W_U[k]), b = across(T_W_U[k + 1]);
    if ((a > 0.0) == (b > 0.0) && a != 0.0) continue;
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 80; ++i) {
      const double mid = 0.5 * (lo + hi);
      const double value = across(interpolatePose(T_W_U[k], T_W_U[k + 1], mid));
      if ((value > 0.0) == (a > 0.0)) {
        lo = mid;
      } else {
        hi = mid;
      }
    }
    const double f = 0.5 * (lo + hi);
    const Eigen::Vector3d p_U = interpolatePose(T_W_U[k], T_W_U[k + 1], f).inverse() * p_W;
    const double u = camera.project(p_U).x();
    if (p_U.z() <= 0.0 || !camera.isInLine(u)) return std::nullopt;
    return Eigen::Vector2d(static_cast<double>(k) + f, u);
  }
  return std::nullopt;
}

class OrthoPixelErrorTest : public ::testing::Test {
 protected:
  OrthoPixelErrorTest()
      : utm_(*fixture_.config().origin),
        camera_(fixture_.calibrationTrue().uhi_camera),
        scene_(testing::trueSeabed()),
        caster_(scene_.vertices, scene_.triangles) {
    for (const LinePose& line : fixture_.linesTrue()) T_W_U_.push_back(line.T);
    const Eigen::Vector2d corner = utm_.nedToUtm(Eigen::Vector3d(kNorthMax, kEastMin, 0.0));
    map_.projection = "UTM";
    map_.easting = corner.x();
    map_.northing = corner.y();
    map_.pixel_size_x = map_.pixel_size_y = kPixel;
    map_.zone = utm_.zone();
    map_.north = utm_.northernHemisphere();
    map_.datum = "WGS-84";
    map_.units = "Meters";
    options_.patch_size_m = kPatch;
  }

  std::filesystem::path ancillaryHdr() const { return fixture_.run() / results_paths::ancillary_hdr; }
  std::filesystem::path orthoHdr() const { return fixture_.run() / results_paths::ortho_hdr; }

  // The pixel centre in W (north, east), as the metric takes it.
  Eigen::Vector2d centreNE(int row, int col) const {
    const Eigen::Vector3d p_W =
        utm_.utmToNed(map_.easting + (col + 0.5) * kPixel, map_.northing - (row + 0.5) * kPixel, 0.0);
    return p_W.head<2>();
  }

  EnviHeader header(int bands) const {
    EnviHeader out;
    out.samples = kCols;
    out.lines = kRows;
    out.bands = bands;
    out.data_type = EnviDataType::float32;
    out.interleave = EnviInterleave::bil;
    out.map_info = map_;
    return out;
  }

  // RUN/hyperspectral/ancillary.hdr (and a one-band ortho.hdr on its grid):
  // every pixel names the line and sample that truly see its centre minus
  // displacement(row, col).
  void writeAncillary(const Displacement& displacement) {
    std::filesystem::create_directories(ancillaryHdr().parent_path());
    EnviWriter writer(ancillaryHdr(), header(4));
    Eigen::MatrixXf line(4, kCols);
    for (int r = 0; r < kRows; ++r) {
      for (int c = 0; c < kCols; ++c) {
        const Eigen::Vector2d seen_NE = centreNE(r, c) - displacement(r, c);
        const auto seen = lineAndSample(Eigen::Vector3d(seen_NE.x(), seen_NE.y(), testing::kSeabedDown), T_W_U_,
                                        camera_);
        ASSERT_TRUE(seen.has_value()) << "pixel (" << r << ", " << c << ") is outside the swath";
        line.col(c) << static_cast<float>(seen->x()), static_cast<float>(seen->y()), kNaN, kNaN;
      }
      writer.writeLine(line);
    }
    writer.finish();
    EnviWriter ortho(orthoHdr(), header(1));
    const Eigen::MatrixXf ortho_line = Eigen::MatrixXf::Constant(1, kCols, 0.5f);
    for (int r = 0; r < kRows; ++r) ortho.writeLine(ortho_line);
    ortho.finish();
  }

  OrthoPixelError measure() const {
    return measureRunOrthoPixelError(orthoHdr(), ancillaryHdr(), T_W_U_, camera_, caster_,
                                     *fixture_.config().origin, options_);
  }

  EvaluationFixture fixture_;
  UtmProjection utm_;
  PushbroomCamera camera_;
  PlyMesh scene_;
  MeshRayCaster caster_;
  std::vector<SE3d> T_W_U_;
  EnviMapInfo map_;
  OrthoPixelErrorOptions options_;
};

double value(const MetricValue& metric) {
  EXPECT_TRUE(metric.value.has_value()) << metric.reason;
  return metric.value.value_or(NAN);
}

TEST_F(OrthoPixelErrorTest, ATruthConsistentAncillaryLayerScoresZero) {
  writeAncillary([](int, int) { return Eigen::Vector2d::Zero(); });
  const OrthoPixelError error = measure();
  std::cout << error.summary() << "\n";
  EXPECT_EQ(error.patch_pixels, 20);
  EXPECT_EQ(error.patches, 8);
  EXPECT_EQ(error.patches_measured, 8);
  EXPECT_EQ(error.pixels_named, kRows * kCols);
  EXPECT_EQ(error.pixels_measured, kRows * kCols);
  // Lines and samples are float32 (~1e-5 line, ~1e-6 sample here): a
  // fraction of a micrometre on the seabed.
  EXPECT_LT(value(error.ortho_pixel_error_abs_m), 1e-6);
  EXPECT_LT(value(error.ortho_pixel_error_m), 1e-6);
  EXPECT_NEAR(*error.scale, 1.0, 1e-6);
}

TEST_F(OrthoPixelErrorTest, AShiftOfTheWholeMapIsInTheAbsoluteFigureOnly) {
  const Eigen::Vector2d shift_NE(0.02, -0.01);
  writeAncillary([&](int, int) -> Eigen::Vector2d { return shift_NE; });
  const OrthoPixelError error = measure();
  std::cout << error.summary() << "\n";
  EXPECT_EQ(error.patches_measured, 8);
  EXPECT_NEAR(value(error.ortho_pixel_error_abs_m), shift_NE.norm(), 1e-6);
  EXPECT_NEAR(error.mean_displacement_NE->x(), shift_NE.x(), 1e-6);
  EXPECT_NEAR(error.mean_displacement_NE->y(), shift_NE.y(), 1e-6);
  // A shift is a similarity: nothing is left once it is removed.
  EXPECT_LT(value(error.ortho_pixel_error_m), 1e-6);
}

TEST_F(OrthoPixelErrorTest, ADistortionThatIsNoSimilarityIsInBothFigures) {
  // The two middle rows of patches land 4 mm east, the outer two 4 mm west:
  // a zig-zag with no mean, no trend along or across (signs +, -, -, + of
  // the patch rows 0..3 sum to 0 and so do their products with the row
  // index), so no similarity absorbs it and every patch keeps its 4 mm.
  constexpr double a = 0.004;
  const int signs[4] = {-1, 1, 1, -1};
  writeAncillary([&](int row, int) -> Eigen::Vector2d { return Eigen::Vector2d(0.0, a * signs[row / 20]); });
  const OrthoPixelError error = measure();
  std::cout << error.summary() << "\n";
  EXPECT_EQ(error.patches_measured, 8);
  EXPECT_NEAR(value(error.ortho_pixel_error_abs_m), a, 1e-6);
  // The seen points move with the distortion, which couples it to the
  // fitted scale at second order (a^2 / var(positions) ~ 1e-4): ~1e-6 m.
  EXPECT_NEAR(value(error.ortho_pixel_error_m), a, 1e-5);
}

TEST_F(OrthoPixelErrorTest, ShiftAndDistortionAddUpInTheAbsoluteFigure) {
  constexpr double a = 0.004;
  const Eigen::Vector2d shift_NE(0.0, 0.03);
  const int signs[4] = {-1, 1, 1, -1};
  writeAncillary([&](int row, int) -> Eigen::Vector2d { return shift_NE + Eigen::Vector2d(0.0, a * signs[row / 20]); });
  const OrthoPixelError error = measure();
  // Patch means 3 cm +- 4 mm east: RMS sqrt(0.03^2 + a^2) with the shift,
  // a without it.
  EXPECT_NEAR(value(error.ortho_pixel_error_abs_m), std::hypot(0.03, a), 1e-6);
  EXPECT_NEAR(value(error.ortho_pixel_error_m), a, 1e-5);
}

TEST_F(OrthoPixelErrorTest, WithoutAnAncillaryLayerOrAnOrthoImageBothAreNullAndSayWhy) {
  OrthoPixelError error = measure();
  EXPECT_EQ(error.ortho_pixel_error_m.reason, kNoOrthoImage);
  EXPECT_EQ(error.ortho_pixel_error_abs_m.reason, kNoOrthoImage);
  writeAncillary([](int, int) { return Eigen::Vector2d::Zero(); });
  std::filesystem::remove(ancillaryHdr());
  error = measure();
  EXPECT_FALSE(error.ortho_pixel_error_m.value.has_value());
  EXPECT_EQ(error.ortho_pixel_error_m.reason, kNoAncillaryLayer);
  EXPECT_EQ(error.ortho_pixel_error_abs_m.reason, kNoAncillaryLayer);
}

TEST_F(OrthoPixelErrorTest, ALineOutsideTheSurveyIsAnInputErrorNamingTheFileAndPixel) {
  std::filesystem::create_directories(ancillaryHdr().parent_path());
  {
    EnviWriter writer(ancillaryHdr(), header(4));
    Eigen::MatrixXf line = Eigen::MatrixXf::Constant(4, kCols, kNaN);
    for (int r = 0; r < kRows; ++r) {
      if (r == 7) line.col(3) << 90.5f, 10.0f, kNaN, kNaN;  // lines are 0 to 89
      writer.writeLine(line);
    }
    writer.finish();
  }
  try {
    measureOrthoPixelError(ancillaryHdr(), T_W_U_, camera_, caster_, *fixture_.config().origin, options_);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), ancillaryHdr());
    const std::string what = e.what();
    EXPECT_NE(what.find("row 7, column 3"), std::string::npos) << what;
    EXPECT_NE(what.find("scan line 90.5 out of range: expected 0 to 89"), std::string::npos) << what;
  }
}

// A gap-filled pixel's line, interpolated in float32, can pass the last line
// by a rounding (1440.000122 on rugged): that is the last line, not an error.
TEST_F(OrthoPixelErrorTest, ALineARoundingPastTheLastIsTheLastLine) {
  std::filesystem::create_directories(ancillaryHdr().parent_path());
  {
    EnviWriter writer(ancillaryHdr(), header(4));
    Eigen::MatrixXf line = Eigen::MatrixXf::Constant(4, kCols, kNaN);
    for (int r = 0; r < kRows; ++r) {
      if (r == 7) line.col(3) << std::nextafter(89.0f, 100.0f), 10.0f, kNaN, kNaN;  // lines are 0 to 89
      writer.writeLine(line);
    }
    writer.finish();
  }
  EXPECT_NO_THROW(
      measureOrthoPixelError(ancillaryHdr(), T_W_U_, camera_, caster_, *fixture_.config().origin, options_));
}

TEST_F(OrthoPixelErrorTest, AnAncillaryLayerOnAnotherGridThanTheOrthoImageIsAnInputError) {
  writeAncillary([](int, int) { return Eigen::Vector2d::Zero(); });
  EnviHeader other = header(1);
  other.lines = kRows + 1;
  {
    EnviWriter ortho(orthoHdr(), other);
    const Eigen::MatrixXf line = Eigen::MatrixXf::Constant(1, kCols, 0.5f);
    for (int r = 0; r < other.lines; ++r) ortho.writeLine(line);
    ortho.finish();
  }
  try {
    measure();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), ancillaryHdr());
    EXPECT_NE(std::string(e.what()).find("not on the grid of"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hsmap
