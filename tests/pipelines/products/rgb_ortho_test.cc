// RgbOrthoRenderer and writeRgbOrtho: colours at the right pixels, empty
// pixels off the mesh, p_W on the surface and exactly under the pixel centre,
// the topmost surface under an overhang, and the PNG and GeoTIFF (georeferencing,
// mask) against the renderer.
#include "pipelines/products/rgb_ortho.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <type_traits>

#include <gdal.h>
#include <ogr_srs_api.h>
#include <opencv2/imgcodecs.hpp>

#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using Rgb = Eigen::Matrix<std::uint8_t, 3, 1>;

const GeodeticPoint kOrigin{43.0, 5.0, 0.0};  // UTM 31N, ~1.4 deg of meridian convergence

// Appends the quad [north0, north1] x [east0, east1] (W) on its own four
// vertices, at down = depth(north, east), coloured colour(north, east).
void addQuad(PlyMesh& mesh, double north0, double north1, double east0, double east1,
             const std::function<double(double, double)>& depth,
             const std::function<Rgb(double, double)>& colour) {
  const int base = int(mesh.vertices.size());
  for (const auto& [n, e] : {std::pair{north0, east0}, std::pair{north0, east1}, std::pair{north1, east1},
                             std::pair{north1, east0}}) {
    mesh.vertices.emplace_back(n, e, depth(n, e));
    mesh.colors.push_back(colour(n, e));
  }
  mesh.triangles.emplace_back(base, base + 1, base + 2);
  mesh.triangles.emplace_back(base, base + 2, base + 3);
}

// A grid of `pixel_m` covering the W box [n0, n1] x [e0, e1] grown by `grow_m`.
OrthoGrid gridAround(const UtmProjection& projection, double n0, double n1, double e0, double e1,
                     double grow_m, double pixel_m) {
  Eigen::AlignedBox2d box;
  for (double n : {n0 - grow_m, n1 + grow_m}) {
    for (double e : {e0 - grow_m, e1 + grow_m}) box.extend(projection.nedToUtm({n, e, 0.0}));
  }
  return OrthoGrid::coveringUtm(box, pixel_m, projection.zone(), projection.northernHemisphere());
}

// The W point on the vertical of pixel (col, row) at down `z` (GeographicLib, exact).
Eigen::Vector3d pixelPoint(const OrthoGrid& grid, const UtmProjection& projection, int col, int row, double z) {
  return grid.wOfPixel(Eigen::Vector2d(col, row), z, projection);
}

TEST(RgbOrtho, FlatMeshShowsItsColoursAtTheRightPixelsAndNothingOffIt) {
  const UtmProjection projection(kOrigin);
  // West half red, east half a blue whose green follows north linearly
  // (exact under barycentric interpolation), 2 m x 2 m at down 3 m.
  PlyMesh mesh;
  auto flat = [](double, double) { return 3.0; };
  addQuad(mesh, -1.0, 1.0, -1.0, 0.0, flat, [](double, double) { return Rgb(255, 0, 0); });
  auto green = [](double n) { return 100.0 + 50.0 * n; };
  addQuad(mesh, -1.0, 1.0, 0.0, 1.0, flat,
          [&](double n, double) { return Rgb(0, std::uint8_t(green(n)), 255); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.2, 0.01);
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  const RgbOrthoPatch patch = renderer.render(0, 0, grid.cols, grid.rows);
  ASSERT_EQ(patch.cols(), grid.cols);
  ASSERT_EQ(patch.rows(), grid.rows);

  int red = 0, blue = 0, empty = 0;
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const Eigen::Vector3d p = pixelPoint(grid, projection, col, row, 3.0);
      const double inside = std::min({1.0 - std::abs(p.x()), 1.0 - std::abs(p.y())});
      if (inside < -1e-6) {
        ASSERT_FALSE(patch.hit(col, row)) << col << ", " << row;
        EXPECT_EQ(patch.bgra.at<cv::Vec4b>(row, col), cv::Vec4b(0, 0, 0, 0));
        EXPECT_TRUE(patch.point(col, row).hasNaN());
        ++empty;
        continue;
      }
      if (inside < 1e-6 || std::abs(p.y()) < 1e-6) continue;  // on an edge: either side
      ASSERT_TRUE(patch.hit(col, row)) << col << ", " << row;
      if (p.y() < 0.0) {
        EXPECT_EQ(patch.rgb(col, row), Rgb(255, 0, 0)) << col << ", " << row;
        ++red;
      } else {
        const Rgb rgb = patch.rgb(col, row);
        EXPECT_EQ(rgb.x(), 0);
        EXPECT_NEAR(rgb.y(), green(p.x()), 0.5 + 1e-6) << col << ", " << row;
        EXPECT_EQ(rgb.z(), 255);
        ++blue;
      }
    }
  }
  // 2 m x 1 m at 1 cm each side, 0.2 m margins around.
  EXPECT_NEAR(red, 20000, 400);
  EXPECT_NEAR(blue, 20000, 400);
  EXPECT_GT(empty, 10000);
}

TEST(RgbOrtho, PointIsOnTheSurfaceUnderThePixelCentreFarFromTheOrigin) {
  const UtmProjection projection(kOrigin);
  // A slope 3 km north-east of the origin: 1.5 m of relief over 3 m, where
  // W's down axis leans ~0.5 mrad from the local vertical.
  const double n0 = 3000.0, e0 = 2000.0;
  auto slope = [&](double n, double e) { return 5.0 + 0.5 * (n - n0) - 0.2 * (e - e0); };
  PlyMesh mesh;
  addQuad(mesh, n0 - 1.5, n0 + 1.5, e0 - 1.0, e0 + 1.0, slope, [](double, double) { return Rgb(9, 9, 9); });
  const OrthoGrid grid = gridAround(projection, n0 - 1.5, n0 + 1.5, e0 - 1.0, e0 + 1.0, 0.1, 0.02);
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  const RgbOrthoPatch patch = renderer.render(0, 0, grid.cols, grid.rows);
  int checked = 0;
  for (int row = 0; row < grid.rows; row += 7) {
    for (int col = 0; col < grid.cols; col += 5) {
      if (!patch.hit(col, row)) continue;
      const Eigen::Vector3d& p = patch.point(col, row);
      EXPECT_NEAR(p.z(), slope(p.x(), p.y()), 1e-9);
      // Its map position is the pixel centre (to 1e-5 pixel, 0.2 um).
      const Eigen::Vector2d at = grid.pixelOfW(p, projection);
      EXPECT_NEAR(at.x(), col, 1e-5);
      EXPECT_NEAR(at.y(), row, 1e-5);
      // And it is the exact point of that vertical at its depth.
      EXPECT_LT((p - pixelPoint(grid, projection, col, row, p.z())).norm(), 1e-6);
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  // Casting along W's +z instead misses by ~|p| dz / R: 1.6 mm here (3 m of ray at 3.6 km).
}

TEST(RgbOrtho, OverhangShowsTheTopmostSurface) {
  const UtmProjection projection(kOrigin);
  PlyMesh mesh;
  // Ground (blue, down 2 m) under a ledge (red, down 1 m) over its north half.
  addQuad(mesh, -1.0, 1.0, -1.0, 1.0, [](double, double) { return 2.0; },
          [](double, double) { return Rgb(0, 0, 255); });
  addQuad(mesh, 0.0, 1.0, -1.0, 1.0, [](double, double) { return 1.0; },
          [](double, double) { return Rgb(255, 0, 0); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.0, 0.02);
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  const RgbOrthoPatch patch = renderer.render(0, 0, grid.cols, grid.rows);
  int ledge = 0, ground = 0;
  for (int row = 0; row < grid.rows; ++row) {
    for (int col = 0; col < grid.cols; ++col) {
      const Eigen::Vector3d p = pixelPoint(grid, projection, col, row, 1.5);
      if (std::abs(p.x()) > 0.99 || std::abs(p.y()) > 0.99 || std::abs(p.x()) < 0.01) continue;
      ASSERT_TRUE(patch.hit(col, row));
      if (p.x() > 0.0) {
        EXPECT_EQ(patch.rgb(col, row), Rgb(255, 0, 0));
        EXPECT_NEAR(patch.point(col, row).z(), 1.0, 1e-9);
        ++ledge;
      } else {
        EXPECT_EQ(patch.rgb(col, row), Rgb(0, 0, 255));
        EXPECT_NEAR(patch.point(col, row).z(), 2.0, 1e-9);
        ++ground;
      }
    }
  }
  EXPECT_GT(ledge, 4000);
  EXPECT_GT(ground, 4000);
}

TEST(RgbOrtho, WindowEqualsThatPartOfTheWholeGrid) {
  const UtmProjection projection(kOrigin);
  PlyMesh mesh;
  addQuad(mesh, -1.0, 1.0, -1.0, 1.0, [](double n, double e) { return 1.0 + 0.3 * n * n + 0.1 * e; },
          [](double n, double e) { return Rgb(std::uint8_t(100 + 90 * n), std::uint8_t(100 + 90 * e), 7); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.1, 0.02);
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  const RgbOrthoPatch whole = renderer.render(0, 0, grid.cols, grid.rows);
  const RgbOrthoPatch window = renderer.render(13, 21, 40, 30);
  EXPECT_EQ(window.col0, 13);
  EXPECT_EQ(window.row0, 21);
  for (int r = 0; r < 30; ++r) {
    for (int c = 0; c < 40; ++c) {
      ASSERT_EQ(window.bgra.at<cv::Vec4b>(r, c), whole.bgra.at<cv::Vec4b>(21 + r, 13 + c));
      if (window.hit(c, r)) {
        EXPECT_EQ(window.point(c, r), whole.point(13 + c, 21 + r));
      }
    }
  }
  // Into reused buffers (a larger window first), and colours alone into a view.
  RgbOrthoPatch reused = renderer.render(0, 0, 60, 50);
  renderer.render(13, 21, 40, 30, reused);
  EXPECT_EQ(reused.col0, 13);
  EXPECT_EQ(reused.row0, 21);
  ASSERT_EQ(reused.p_W.size(), 40u * 30u);
  EXPECT_EQ(cv::norm(reused.bgra, window.bgra, cv::NORM_INF), 0.0);
  for (std::size_t i = 0; i < reused.p_W.size(); ++i) {
    if (!window.p_W[i].hasNaN()) {
      EXPECT_EQ(reused.p_W[i], window.p_W[i]);
    }
    EXPECT_EQ(reused.p_W[i].hasNaN(), window.p_W[i].hasNaN());
  }
  cv::Mat image(grid.rows, grid.cols, CV_8UC4, cv::Scalar::all(77));
  cv::Mat view = image(cv::Rect(13, 21, 40, 30));
  renderer.renderColours(13, 21, 40, 30, view);
  EXPECT_EQ(view.data, image.ptr(21, 13));  // rendered in place
  EXPECT_EQ(cv::norm(view, window.bgra, cv::NORM_INF), 0.0);

  EXPECT_THROW(renderer.render(grid.cols - 5, 0, 6, 1), std::invalid_argument);
  EXPECT_THROW(renderer.render(0, 0, 0, 1), std::invalid_argument);
  EXPECT_THROW(renderer.render(-1, 0, 2, 1), std::invalid_argument);
}

// A renderer casting through a caster built apart (the products stage's)
// renders the same as one building its own; a caster of another mesh is refused.
TEST(RgbOrtho, ASharedCasterRendersAsTheRenderersOwnAndMustHoldTheMesh) {
  const UtmProjection projection(kOrigin);
  PlyMesh mesh;
  addQuad(mesh, -1.0, 1.0, -1.0, 1.0, [](double n, double e) { return 1.0 + 0.2 * n * e; },
          [](double n, double e) { return Rgb(std::uint8_t(120 + 60 * n), 9, std::uint8_t(120 + 60 * e)); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.1, 0.02);
  const RgbOrthoPatch own = RgbOrthoRenderer(mesh, grid, projection).render(0, 0, grid.cols, grid.rows);
  const MeshRayCaster caster(mesh.vertices, mesh.triangles);
  const RgbOrthoPatch shared = RgbOrthoRenderer(mesh, caster, grid, projection).render(0, 0, grid.cols, grid.rows);
  EXPECT_EQ(cv::norm(own.bgra, shared.bgra, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::countNonZero(own.bgra.reshape(1) != 0), 0);

  PlyMesh larger = mesh;
  addQuad(larger, 2.0, 3.0, 2.0, 3.0, [](double, double) { return 1.0; }, [](double, double) { return Rgb(1, 1, 1); });
  const MeshRayCaster other(larger.vertices, larger.triangles);
  EXPECT_THROW(RgbOrthoRenderer(mesh, other, grid, projection), std::invalid_argument);
}

struct GdalCloser {
  void operator()(GDALDatasetH dataset) const { GDALClose(dataset); }
};

TEST(RgbOrtho, PngAndGeoTiffHoldTheRenderingOnTheGridsGeoreferencing) {
  const UtmProjection projection(kOrigin);
  PlyMesh mesh;
  addQuad(mesh, -1.0, 1.0, -1.0, 1.0, [](double, double) { return 1.0; },
          [](double n, double e) { return Rgb(std::uint8_t(120 + 100 * n), std::uint8_t(120 + 100 * e), 60); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.25, 0.01);
  const RgbOrthoRenderer renderer(mesh, grid, projection);
  const RgbOrthoPatch whole = renderer.render(0, 0, grid.cols, grid.rows);

  testing::TempFolder folder;
  RgbOrthoOptions options;
  options.band_pixels = 7 * grid.cols + 3;  // 7 rows, rounded up to a row of tiles
  options.geotiff_block_size = 64;          // several tiles and overview levels
  ASSERT_GT(grid.rows % 64, 0);             // the last band is short
  const RgbOrthoReport report = writeRgbOrtho(renderer, folder.path() / "map", options);
  EXPECT_EQ(report.band_rows, 64);
  EXPECT_EQ(report.bands, (grid.rows + 63) / 64);
  EXPECT_EQ(report.pixels, grid.pixelCount());
  EXPECT_EQ(report.hits, cv::countNonZero([&] {
              cv::Mat alpha;
              cv::extractChannel(whole.bgra, alpha, 3);
              return alpha;
            }()));
  EXPECT_GT(report.hits, 0);
  EXPECT_LT(report.hits, report.pixels);
  EXPECT_NE(report.summary().find("RGB ortho-image"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "map" / "rgb_ortho.png.partial"));
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "map" / "rgb_ortho.tif.partial"));

  // The PNG is the rendering, RGBA, also from bands of 7 rows.
  const cv::Mat png = cv::imread((folder.path() / "map" / "rgb_ortho.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(png.type(), CV_8UC4);
  EXPECT_EQ(cv::norm(png, whole.bgra, cv::NORM_INF), 0.0);
  options.write_geotiff = false;
  const RgbOrthoReport png_only = writeRgbOrtho(renderer, folder.path() / "png_only", options);
  EXPECT_EQ(png_only.band_rows, 7);
  EXPECT_TRUE(png_only.tif.empty());
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "png_only" / "rgb_ortho.tif"));
  EXPECT_EQ(cv::norm(cv::imread(png_only.png.string(), cv::IMREAD_UNCHANGED), whole.bgra, cv::NORM_INF), 0.0);

  // The GeoTIFF: the grid's geotransform and UTM CRS, R, G, B bands, the mask.
  std::unique_ptr<std::remove_pointer_t<GDALDatasetH>, GdalCloser> tif(
      GDALOpen((folder.path() / "map" / "rgb_ortho.tif").c_str(), GA_ReadOnly));
  ASSERT_NE(tif, nullptr);
  EXPECT_STREQ(GDALGetDriverShortName(GDALGetDatasetDriver(tif.get())), "GTiff");
  double transform[6];
  ASSERT_EQ(GDALGetGeoTransform(tif.get(), transform), CE_None);
  EXPECT_EQ(transform[0], grid.west_m);
  EXPECT_EQ(transform[1], grid.pixel_m);
  EXPECT_EQ(transform[2], 0.0);
  EXPECT_EQ(transform[3], grid.north_m);
  EXPECT_EQ(transform[4], 0.0);
  EXPECT_EQ(transform[5], -grid.pixel_m);
  ASSERT_EQ(GDALGetRasterXSize(tif.get()), grid.cols);
  ASSERT_EQ(GDALGetRasterYSize(tif.get()), grid.rows);
  ASSERT_EQ(GDALGetRasterCount(tif.get()), 3);
  OGRSpatialReferenceH srs = GDALGetSpatialRef(tif.get());
  ASSERT_NE(srs, nullptr);
  EXPECT_STREQ(OSRGetAuthorityCode(srs, nullptr), "32631");
  const GDALColorInterp interp[3] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand};
  for (int b = 0; b < 3; ++b) {
    GDALRasterBandH band = GDALGetRasterBand(tif.get(), b + 1);
    EXPECT_EQ(GDALGetRasterDataType(band), GDT_Byte);
    EXPECT_EQ(GDALGetRasterColorInterpretation(band), interp[b]);
    EXPECT_EQ(GDALGetMaskFlags(band), GMF_PER_DATASET);
    EXPECT_GE(GDALGetOverviewCount(band), 2);
    cv::Mat values(grid.rows, grid.cols, CV_8UC1);
    ASSERT_EQ(GDALRasterIO(band, GF_Read, 0, 0, grid.cols, grid.rows, values.data, grid.cols, grid.rows,
                           GDT_Byte, 0, 0),
              CE_None);
    cv::Mat expected;
    cv::extractChannel(whole.bgra, expected, 2 - b);
    EXPECT_EQ(cv::norm(values, expected, cv::NORM_INF), 0.0) << "band " << b + 1;
  }
  cv::Mat mask(grid.rows, grid.cols, CV_8UC1);
  ASSERT_EQ(GDALRasterIO(GDALGetMaskBand(GDALGetRasterBand(tif.get(), 1)), GF_Read, 0, 0, grid.cols, grid.rows,
                         mask.data, grid.cols, grid.rows, GDT_Byte, 0, 0),
            CE_None);
  cv::Mat alpha;
  cv::extractChannel(whole.bgra, alpha, 3);
  EXPECT_EQ(cv::norm(mask, alpha, cv::NORM_INF), 0.0);
}

TEST(RgbOrtho, RejectsAMeshWithoutColoursAGridInAnotherZoneAndBadOptions) {
  const UtmProjection projection(kOrigin);
  PlyMesh mesh;
  addQuad(mesh, -1.0, 1.0, -1.0, 1.0, [](double, double) { return 1.0; },
          [](double, double) { return Rgb(1, 2, 3); });
  const OrthoGrid grid = gridAround(projection, -1.0, 1.0, -1.0, 1.0, 0.0, 0.05);
  PlyMesh grey = mesh;
  grey.colors.clear();
  EXPECT_THROW(RgbOrthoRenderer(grey, grid, projection), std::invalid_argument);
  OrthoGrid other = grid;
  other.zone = 32;
  EXPECT_THROW(RgbOrthoRenderer(mesh, other, projection), std::invalid_argument);

  RgbOrthoOptions options;
  EXPECT_NO_THROW(options.validate());
  options.band_pixels = 0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = {};
  options.geotiff_block_size = 100;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = {};
  options.geotiff_compression = "JPEG";
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options = {};
  options.margin_m = 0.0;
  EXPECT_THROW(options.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
