// Spectra that are NaN in a band, or hold the cube's `data ignore value`, are
// counted and never painted into the ortho-image.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "pipelines/products/hyperspectral_ortho.h"
#include "pipelines/products/scan_line_caster.h"
#include "tests/support/spoiled_cube.h"
#include "tests/support/tiny_products_fixture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::tinyProductsSurvey;

constexpr int kNanSample = 100;     // band 3 NaN in every line
constexpr int kIgnoreSample = 50;   // every band = the data ignore value
constexpr float kIgnoreValue = -1.0f;

// A float32 copy of the survey's cube with the two samples spoiled.
std::filesystem::path spoiledCube(const EnviReader& cube, const std::filesystem::path& folder) {
  return testing::spoiledFloatCube(cube, folder, kIgnoreValue, [](int, Eigen::MatrixXf& line) {
    line(3, kNanSample) = std::numeric_limits<float>::quiet_NaN();
    line.col(kIgnoreSample).setConstant(kIgnoreValue);
  });
}

TEST(InvalidSpectra, AreCountedAndNotPainted) {
  testing::TempFolder folder;
  Survey survey = loadSurvey(tinyProductsSurvey().folder);
  survey.cube = std::make_unique<EnviReader>(spoiledCube(*survey.cube, folder.path()));

  // How many hits the two samples have (the same casting the stage does).
  const PlyMesh ply = readPly(tinyProductsSurvey().scene_ply);
  const MeshRayCaster mesh(ply.vertices, ply.triangles);
  const PushbroomCamera camera(survey.config.uhi.camera);
  const ScanLineCaster caster(camera, mesh);
  std::int64_t nan_hits = 0, ignore_hits = 0;
  ScanLineHits hits;
  for (const LinePose& pose : tinyProductsSurvey().true_line_poses) {
    caster.castLine(pose.line, pose.T, hits);
    nan_hits += hits.hit(kNanSample) ? 1 : 0;
    ignore_hits += hits.hit(kIgnoreSample) ? 1 : 0;
  }
  ASSERT_GT(nan_hits, 50);
  ASSERT_GT(ignore_hits, 50);

  HyperspectralOptions options;
  options.write_geotiff = false;
  options.write_quicklook = false;
  std::ostringstream log;
  const HyperspectralReport report = writeHyperspectralProducts(
      survey, tinyProductsSurvey().true_line_poses, tinyProductsSurvey().scene_ply, folder / "out", options, log);
  EXPECT_EQ(report.skipped_non_finite, nan_hits);
  EXPECT_EQ(report.skipped_ignore_value, ignore_hits);
  EXPECT_EQ(report.painted, report.hits - nan_hits - ignore_hits);

  // No ortho pixel comes from the spoiled samples, and no value is NaN in
  // some bands only or holds the ignore value.
  const EnviReader ortho(folder / "out" / "ortho.hdr");
  const EnviReader ancillary(folder / "out" / "ancillary.hdr");
  Eigen::MatrixXf o, a;
  std::int64_t valid = 0, on_spoiled_sample = 0;
  for (int r = 0; r < ortho.lines(); ++r) {
    ortho.readLine(r, o);
    ancillary.readLine(r, a);
    for (int c = 0; c < ortho.samples(); ++c) {
      const bool any_finite = o.col(c).array().isFinite().any();
      if (!any_finite) continue;
      ++valid;
      ASSERT_TRUE(o.col(c).array().isFinite().all()) << r << " " << c;
      ASSERT_FALSE((o.col(c).array() == kIgnoreValue).any()) << r << " " << c;
      // An observed pixel's sample is that of its nearest painted hit, never
      // a spoiled one; a gap-filled pixel's is interpolated between its
      // sources' (49 and 51 give 50), so only a fractional or in-between
      // value can fall on a spoiled sample: never one of a painted hit.
      if (a(1, c) == float(kNanSample) || a(1, c) == float(kIgnoreSample)) ++on_spoiled_sample;
    }
  }
  EXPECT_GT(valid, 1000);
  // Those in-between pixels are few: the spoiled samples' hits would be
  // hundreds (nan_hits, ignore_hits above).
  EXPECT_LT(on_spoiled_sample, std::min(nan_hits, ignore_hits) / 4);
}

}  // namespace
}  // namespace hsmap
