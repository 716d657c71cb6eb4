// Tie points in the push-broom strip (strip_tie_points.h) on the `tiny`
// simulated survey: with the scan lines posed a known distance off, each tie
// point must name the surface point that the real pixel saw (found by
// casting the pixel's ray from its true pose), not the one the wrong pose
// predicts.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/io/envi_reader.h"
#include "core/io/ply_io.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/pose_tables.h"
#include "core/survey/survey.h"
#include "pipelines/products/scan_line_caster.h"
#include "pipelines/calibration/strip_tie_points.h"
#include "core/util/median.h"
#include "tests/support/spoiled_cube.h"
#include "tests/support/tiny_products_fixture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::tinyProductsSurvey;

// `tiny`'s UHI has 240 samples (8 mm at 1.5 m) and its lines are 10 mm
// apart: single-sample columns and patches of about 0.25 x 0.15 m.
StripTiePointOptions tinyOptions() {
  StripTiePointOptions options;
  options.sample_step = 1;
  options.patch_lines = 15;
  options.patch_columns = 31;
  options.search_lines = 3;
  options.search_columns = 6;
  return options;
}

struct TinyStrip {
  Survey survey = loadSurvey(tinyProductsSurvey().folder);
  PlyMesh scene = readPly(tinyProductsSurvey().scene_ply);
  MeshRayCaster mesh{scene.vertices, scene.triangles};
  PushbroomCamera uhi{survey.config.uhi.camera};
  PinholeRadtanCamera rgb{survey.config.rgb.camera};
  std::vector<LinePose> true_lines = tinyProductsSurvey().true_line_poses;

  // Lines posed with T_W_U * offset_U (the true frames and surface).
  StripTiePointInputs inputs(const SE3d& offset_U) const {
    StripTiePointInputs in;
    in.cube = survey.cube.get();
    // Equal weights over 450-650 nm: a luminance-like combination.
    in.band_weights.assign(survey.wavelengths_nm.size(), 0.0);
    for (std::size_t b = 0; b < survey.wavelengths_nm.size(); ++b) {
      if (survey.wavelengths_nm[b] >= 450.0 && survey.wavelengths_nm[b] <= 650.0) in.band_weights[b] = 1.0;
    }
    in.uhi_camera = &uhi;
    for (const LinePose& line : true_lines) in.lines.push_back({line.line, line.t, line.T * offset_U});
    in.mesh = &mesh;
    in.frames = &survey.rgb;
    in.rgb_camera = &rgb;
    const std::vector<TimedPose> frames =
        readTimedPoseTable(tinyProductsSurvey().folder / "truth" / "rgb_poses.csv");
    for (int i = 0; i < survey.rgb.frameCount() && i < int(frames.size()); ++i) {
      in.frame_poses.emplace_back(i, frames[std::size_t(i)].T);
    }
    return in;
  }

  // Where the real pixel (line, sample) looked: its ray from the true pose.
  Eigen::Vector3d trueHit(long long line, double sample) const {
    return hitFrom(true_lines.at(std::size_t(line)).T, sample);
  }
  // Where pixel `sample` of a line posed at T_W_U looks (NaN: a miss).
  Eigen::Vector3d hitFrom(const SE3d& T_W_U, double sample) const {
    Ray ray;
    ray.origin = T_W_U.t;
    ray.direction = T_W_U.q * *uhi.unproject(sample);
    ray.t_near = 0.05;
    const RayHit hit = mesh.intersect(ray);
    return hit.triangle >= 0 ? Eigen::Vector3d(ray.origin + hit.distance * ray.direction)
                             : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  }
};

// A float32 copy of `cube` with dead samples as another sensor would have
// them: two adjacent sample columns at the data ignore value in every line
// and band, and about one pixel in a hundred NaN in every band.
std::filesystem::path cubeWithDeadPixels(const EnviReader& cube, const std::filesystem::path& folder) {
  return testing::spoiledFloatCube(cube, folder, -1.0f, [&](int l, Eigen::MatrixXf& line) {
    line.col(100).setConstant(-1.0f);
    line.col(101).setConstant(-1.0f);
    for (int s = 0; s < cube.samples(); ++s) {
      if ((7 * l + s) % 97 == 0) line.col(s).setConstant(std::numeric_limits<float>::quiet_NaN());
    }
  });
}

TEST(StripTiePoints, TieEachRealPixelToThePointItSawDespiteAWrongLinePose) {
  const TinyStrip strip;
  // 12 mm across the line (1.5 samples) and 5 mm along it.
  const SE3d offset_U(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.012, 0.005, 0.0));
  std::ostringstream log;
  const StripTiePoints found = findStripTiePoints(strip.inputs(offset_U), tinyOptions(), log);
  SCOPED_TRACE(log.str());
  ASSERT_GE(found.counts.tie_points, 8);  // of 24 patches
  EXPECT_NEAR(found.counts.across_pixel_m, 1.5 / strip.uhi.parameters().f, 0.003);

  std::vector<double> tie_errors, predicted_errors;
  for (const ExtrinsicTiePoint& tie : found.tie_points) {
    const Eigen::Vector3d truth = strip.trueHit(tie.line, tie.sample);
    ASSERT_TRUE(truth.allFinite());
    tie_errors.push_back((tie.p_W - truth).norm());
    // What the wrong pose alone says the pixel saw.
    const Eigen::Vector3d predicted =
        strip.hitFrom(strip.true_lines.at(std::size_t(tie.line)).T * offset_U, tie.sample);
    ASSERT_TRUE(predicted.allFinite());
    predicted_errors.push_back((predicted - truth).norm());
  }
  // The prediction is off by the offset; the tie points by less than a
  // third of the strip's pixel (6.3 mm across, 13.7 mm along).
  EXPECT_GT(upperMedian(predicted_errors), 0.010);
  EXPECT_LT(upperMedian(tie_errors), 0.002);
}

TEST(StripTiePoints, PhasesBetweenTheLinesFindTheShiftAlongTheTrackFinerThanTheLines) {
  const TinyStrip strip;
  // 6 mm along the track: under half of tiny's 13.7 mm line spacing.
  const SE3d offset_U(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.0, 0.006, 0.0));
  StripTiePointOptions options = tinyOptions();
  options.line_phases = 4;
  std::ostringstream log;
  const StripTiePoints found = findStripTiePoints(strip.inputs(offset_U), options, log);
  SCOPED_TRACE(log.str());
  ASSERT_GE(found.counts.tie_points, 8);
  std::vector<double> along_errors;
  for (const ExtrinsicTiePoint& tie : found.tie_points) {
    const SE3d& T_W_U = strip.true_lines.at(std::size_t(tie.line)).T;
    const Eigen::Vector3d truth = strip.trueHit(tie.line, tie.sample);
    ASSERT_TRUE(truth.allFinite());
    along_errors.push_back(std::abs((T_W_U.q.inverse() * (tie.p_W - truth)).y()));
  }
  // Matched on the lines alone (line_phases 1), the sub-pixel peak is
  // pulled towards whole lines: 4 patches match here, and in the test
  // above the median error along the track is 2.4 mm. A quarter-line grid
  // gets within 1 mm.
  EXPECT_LT(upperMedian(along_errors), 0.001);
}

TEST(StripTiePoints, RejectsBandWeightsThatDoNotMatchTheCube) {
  const TinyStrip strip;
  StripTiePointInputs in = strip.inputs(SE3d());
  in.band_weights.pop_back();
  std::ostringstream log;
  try {
    findStripTiePoints(in, tinyOptions(), log);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_EQ(std::string(error.what()),
              "findStripTiePoints: " + std::to_string(in.band_weights.size()) +
                  " band weights for a cube of " + std::to_string(in.band_weights.size() + 1) +
                  " bands");
  }
}

TEST(StripTiePoints, OptionsNameTheFieldThatIsWrong) {
  StripTiePointOptions options;
  options.search_columns = 0;
  EXPECT_THROW(
      {
        try {
          options.validate();
        } catch (const std::invalid_argument& error) {
          EXPECT_STREQ(error.what(),
                       "StripTiePointOptions: search_lines and search_columns must be >= 1");
          throw;
        }
      },
      std::invalid_argument);
}

// A patch must be valid throughout; without the interpolation of short
// runs a dead sample column and scattered bad pixels (one in a hundred)
// leave almost no patch to match.
TEST(StripTiePoints, DeadSamplesAreInterpolatedInsteadOfRemovingEveryPatchTheyFallIn) {
  testing::TempFolder folder;
  TinyStrip strip;
  const SE3d offset_U(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.012, 0.005, 0.0));
  std::ostringstream log;
  const int clean = findStripTiePoints(strip.inputs(offset_U), tinyOptions(), log).counts.tie_points;
  ASSERT_GE(clean, 8);

  strip.survey.cube = std::make_unique<EnviReader>(cubeWithDeadPixels(*strip.survey.cube, folder.path()));
  StripTiePointOptions no_fill = tinyOptions();
  no_fill.fill_invalid_columns = 0;
  const StripTiePoints without = findStripTiePoints(strip.inputs(offset_U), no_fill, log);
  EXPECT_LT(without.counts.tie_points, clean / 4) << log.str();

  const StripTiePoints with = findStripTiePoints(strip.inputs(offset_U), tinyOptions(), log);
  SCOPED_TRACE(log.str());
  EXPECT_GT(with.counts.filled_pixels, 2 * strip.survey.cube->lines());
  EXPECT_GE(with.counts.tie_points, clean - 2);
  std::vector<double> errors;
  for (const ExtrinsicTiePoint& tie : with.tie_points) {
    errors.push_back((tie.p_W - strip.trueHit(tie.line, tie.sample)).norm());
  }
  ASSERT_FALSE(errors.empty());
  EXPECT_LT(upperMedian(errors), 0.002);
}

}  // namespace
}  // namespace hsmap
