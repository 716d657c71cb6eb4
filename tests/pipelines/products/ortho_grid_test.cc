// OrthoGrid: snapping, W <-> pixel round trips, map info; WToUtmLattice against
// the exact projection.
#include "pipelines/products/ortho_grid.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pipelines/products/w_to_utm_lattice.h"

namespace hsmap {
namespace {

const GeodeticPoint kOrigin{43.0, 5.0, 0.0};

TEST(OrthoGrid, CornerIsSnappedToThePixelSizeAndCoversTheFootprint) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(500123.4567, 4761234.5678),
                                Eigen::Vector2d(500125.0001, 4761240.0));
  const OrthoGrid grid = OrthoGrid::coveringUtm(box, 0.005, 31, true);
  EXPECT_NEAR(std::remainder(grid.west_m, 0.005), 0.0, 1e-9);
  EXPECT_NEAR(std::remainder(grid.north_m, 0.005), 0.0, 1e-9);
  EXPECT_LE(grid.west_m, box.min().x());
  EXPECT_GT(grid.north_m, box.max().y());
  EXPECT_GT(grid.west_m + grid.cols * grid.pixel_m, box.max().x());
  EXPECT_LE(grid.north_m - grid.rows * grid.pixel_m, box.min().y());
  EXPECT_TRUE(grid.contains(grid.containingPixel(box.min())));
  EXPECT_TRUE(grid.contains(grid.containingPixel(box.max())));
  EXPECT_EQ(grid.containingPixel(Eigen::Vector2d(grid.west_m + 0.0001, grid.north_m - 0.0001)),
            Eigen::Vector2i(0, 0));
}

TEST(OrthoGrid, MapInfoIsUtmOnWgs84WithTheCorner) {
  const OrthoGrid grid = OrthoGrid::coveringUtm(
      Eigen::AlignedBox2d(Eigen::Vector2d(10.0, 20.0), Eigen::Vector2d(11.0, 21.0)), 0.01, 33, false);
  const EnviMapInfo info = grid.mapInfo();
  EXPECT_EQ(info.projection, "UTM");
  EXPECT_EQ(info.reference_pixel_x, 1);
  EXPECT_EQ(info.reference_pixel_y, 1);
  EXPECT_DOUBLE_EQ(info.easting, grid.west_m);
  EXPECT_DOUBLE_EQ(info.northing, grid.north_m);
  EXPECT_DOUBLE_EQ(info.pixel_size_x, 0.01);
  EXPECT_DOUBLE_EQ(info.pixel_size_y, 0.01);
  EXPECT_EQ(info.zone, 33);
  EXPECT_FALSE(info.north);
  EXPECT_EQ(info.datum, "WGS-84");
  EXPECT_EQ(info.units, "Meters");
  // The header writer and reader agree on it.
  EnviHeader header;
  header.samples = grid.cols;
  header.lines = grid.rows;
  header.bands = 1;
  header.map_info = info;
  const EnviHeader back = parseEnviHeader(formatEnviHeader(header), "ortho.hdr");
  ASSERT_TRUE(back.map_info.has_value());
  EXPECT_EQ(*back.map_info, info);
}

TEST(OrthoGrid, WorldPointToPixelAndBackWithinHalfAPixel) {
  const UtmProjection projection(kOrigin);
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-30.0, -40.0, 20.0), Eigen::Vector3d(50.0, 60.0, 20.0)}) {
    box.extend(projection.nedToUtm(p));
  }
  const OrthoGrid grid =
      OrthoGrid::coveringUtm(box, 0.005, projection.zone(), projection.northernHemisphere());
  for (const Eigen::Vector3d& p_W : {Eigen::Vector3d(-29.99, -39.98, 20.0), Eigen::Vector3d(0.0, 0.0, 21.0),
                                    Eigen::Vector3d(12.3456, -7.891, 19.5), Eigen::Vector3d(49.9, 59.9, 20.0)}) {
    const Eigen::Vector2d col_row = grid.pixelOfW(p_W, projection);
    const Eigen::Vector2i pixel = grid.containingPixel(projection.nedToUtm(p_W));
    ASSERT_TRUE(grid.contains(pixel));
    // The containing pixel's centre is within half a pixel (each axis) in the map...
    EXPECT_LE(std::abs(col_row.x() - pixel.x()), 0.5 + 1e-9);
    EXPECT_LE(std::abs(col_row.y() - pixel.y()), 0.5 + 1e-9);
    // ... and back in W: the centre lies within half a pixel diagonal (times the point scale).
    const Eigen::Vector3d centre_W = grid.wOfPixel(pixel.cast<double>(), p_W.z(), projection);
    EXPECT_LE((centre_W - p_W).head<2>().norm(), 0.5 * std::sqrt(2.0) * grid.pixel_m * 1.001);
    EXPECT_NEAR(centre_W.z(), p_W.z(), 1e-9);
    // Continuous coordinates round-trip exactly.
    const Eigen::Vector3d back = grid.wOfPixel(col_row, p_W.z(), projection);
    EXPECT_LT((back - p_W).norm(), 1e-6);
  }
}

TEST(OrthoGrid, RefusesBadInput) {
  const Eigen::AlignedBox2d box(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_THROW(OrthoGrid::coveringUtm(box, 0.0, 31, true), std::invalid_argument);
  EXPECT_THROW(OrthoGrid::coveringUtm(Eigen::AlignedBox2d(), 0.005, 31, true), std::invalid_argument);
  EXPECT_THROW(OrthoGrid::coveringUtm(box, 0.005, 0, true), std::invalid_argument);
  const UtmProjection projection(kOrigin);
  const OrthoGrid other = OrthoGrid::coveringUtm(box, 0.005, projection.zone() + 1, true);
  EXPECT_THROW(other.pixelOfW(Eigen::Vector3d::Zero(), projection), std::invalid_argument);
}

TEST(WToUtmLattice, AgreesWithTheExactProjectionToAMicrometre) {
  const UtmProjection projection(kOrigin);
  const Eigen::AlignedBox2d box(Eigen::Vector2d(-200.0, -50.0), Eigen::Vector2d(300.0, 80.0));
  const WToUtmLattice lattice(projection, box, 20.0);
  double worst = 0.0;
  for (int i = 0; i <= 40; ++i) {
    for (int j = 0; j <= 40; ++j) {
      const Eigen::Vector3d p(-200.0 + 500.0 * i / 40.0 + 0.37, -50.0 + 130.0 * j / 40.0 + 0.11,
                              20.0 + 0.5 * std::sin(i));
      worst = std::max(worst, (lattice.toUtm(p) - projection.nedToUtm(p)).norm());
    }
  }
  EXPECT_LT(worst, 1e-6);
  // Outside the lattice: exact.
  const Eigen::Vector3d far(5000.0, 5000.0, 20.0);
  EXPECT_LT((lattice.toUtm(far) - projection.nedToUtm(far)).norm(), 1e-9);
}

}  // namespace
}  // namespace hsmap
