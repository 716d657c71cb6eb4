// A mesh that only lies under one half of the swath: the other half's rays
// miss, are counted, and the ortho-image is empty (NaN) there.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "pipelines/products/hyperspectral_ortho.h"
#include "tests/support/tiny_products_fixture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::tinyProductsSurvey;

TEST(MeshMisses, AreCountedAndLeaveTheOrthoEmpty) {
  testing::TempFolder folder;
  const std::vector<LinePose>& poses = tinyProductsSurvey().true_line_poses;
  const SE3d T_U_W = poses[poses.size() / 2].T.inverse();
  // Keep the triangles on the +x_U side of the middle scan line.
  const PlyMesh scene = readPly(tinyProductsSurvey().scene_ply);
  PlyMesh half;
  half.vertices = scene.vertices;
  for (const Eigen::Vector3i& t : scene.triangles) {
    const Eigen::Vector3d centroid =
        (scene.vertices[std::size_t(t[0])] + scene.vertices[std::size_t(t[1])] + scene.vertices[std::size_t(t[2])]) / 3.0;
    if ((T_U_W * centroid).x() > 0.0) half.triangles.push_back(t);
  }
  ASSERT_FALSE(half.triangles.empty());
  writePly(folder / "half.ply", half);

  const Survey survey = loadSurvey(tinyProductsSurvey().folder);
  HyperspectralOptions options;
  options.write_geotiff = false;
  options.write_quicklook = false;
  std::ostringstream log;
  const HyperspectralReport report =
      writeHyperspectralProducts(survey, poses, folder / "half.ply", folder / "out", options, log);
  EXPECT_EQ(report.pixels_cast, report.hits + report.misses);
  EXPECT_GT(report.misses, 0.35 * double(report.pixels_cast));
  EXPECT_GT(report.hits, 0.35 * double(report.pixels_cast));

  // Valid pixels only where the mesh is (x_U > 0, within the filling radius
  // and the track's wobble); the grid reaches no farther than the hits.
  const UtmProjection projection(survey.origin);
  const EnviReader ortho(folder / "out" / "ortho.hdr");
  Eigen::MatrixXf line;
  std::int64_t valid = 0, on_missing_side = 0;
  double lowest_x = 1e9;
  for (int r = 0; r < ortho.lines(); ++r) {
    ortho.readLine(r, line);
    for (int c = 0; c < ortho.samples(); ++c) {
      const Eigen::Vector3d p_W = report.grid.wOfPixel(Eigen::Vector2d(c, r), 0.0, projection);
      const double x_U = (T_U_W * Eigen::Vector3d(p_W.x(), p_W.y(), T_U_W.inverse().t.z() + 1.5)).x();
      lowest_x = std::min(lowest_x, x_U);
      if (!std::isfinite(line(0, c))) continue;
      ++valid;
      if (x_U < -0.05) ++on_missing_side;
    }
  }
  EXPECT_GT(valid, 1000);
  EXPECT_EQ(on_missing_side, 0);
  EXPECT_GT(lowest_x, -0.2);
}

}  // namespace
}  // namespace hsmap
