// Collecting the report's data from run folder files: the histograms, the
// truth's metrics and displacement field, the trajectory's keyframes and
// tracking losses, the spectral grid and the mesh seen from above.
#include <gtest/gtest.h>

#include <cmath>

#include "core/io/envi_writer.h"
#include "core/survey/pose_tables.h"
#include "pipelines/report/collect_trajectory.h"
#include "pipelines/report/collect_truth.h"
#include "pipelines/report/mesh_top_view.h"
#include "pipelines/report/report_histogram.h"
#include "pipelines/report/spectral_grid.h"
#include "tests/support/expect_input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::expectInputError;
using testing::TempFolder;
using testing::writeText;

TEST(BinResiduals, CountsEveryValueOnceWithItsOutliersAndWhatLiesBeyond) {
  std::vector<double> values;
  for (int i = 0; i < 98; ++i) values.push_back(0.01 * i);  // 0 .. 0.97
  values.push_back(5.0);
  values.push_back(NAN);
  values.push_back(1.5);
  std::vector<bool> outlier(values.size(), false);
  for (std::size_t i = 0; i < values.size(); ++i) outlier[i] = values[i] > 0.5;
  const ReportHistogram h = binResiduals("reprojection", "px", values, outlier, 0.5, "beyond 0.5 px");
  ASSERT_EQ(h.counts.size(), 40u);
  EXPECT_EQ(h.total, 100);  // NaN skipped
  EXPECT_DOUBLE_EQ(h.bin_width, 1.5 / 40);  // the 99th percentile (1.5) is above 2 x the threshold
  long long counted = h.beyond, outliers = h.beyond_outliers;
  for (std::size_t i = 0; i < h.counts.size(); ++i) {
    counted += h.counts[i];
    outliers += h.outlier_counts[i];
  }
  EXPECT_EQ(counted, 100);
  EXPECT_EQ(h.beyond, 2);  // 5.0 and 1.5 (at the range's end)
  EXPECT_EQ(outliers, h.outliers);
  EXPECT_EQ(h.outliers, 47 + 2);
}

TEST(CollectTruth, ReadsEveryMetricInOrderAndTheDisplacementField) {
  TempFolder run;
  writeText(run.path() / "metrics.json",
            "{\n  \"variant\": \"sequential\",\n  \"rgb_ate_m\": 0.5,\n  \"ortho_scale_error\": null,\n"
            "  \"uhi_distortion_error\": [0.1, 0.2],\n  \"timings_s\": {\"georef\": 3.2, \"total\": 15.9}\n}\n");
  writeText(run.path() / "report" / "ortho_patches.csv",
            "north_m,east_m,displacement_north_m,displacement_east_m,response\n1.33,-0.29,-0.061,-0.0016,0.99\n");
  ReportData data;
  collectTruth(run.path(), data);
  ASSERT_EQ(data.metrics.size(), 6u);
  EXPECT_EQ(data.metrics[0].first, "rgb_ate_m");
  EXPECT_EQ(data.metrics[0].second, 0.5);
  EXPECT_EQ(data.metrics[1].first, "ortho_scale_error");
  EXPECT_FALSE(data.metrics[1].second.has_value());
  EXPECT_EQ(data.metrics[3].first, "uhi_distortion_error[1]");
  EXPECT_EQ(data.metrics[5].first, "timings_s.total");
  EXPECT_EQ(data.metrics[5].second, 15.9);
  ASSERT_EQ(data.ortho_patches.size(), 1u);
  EXPECT_EQ(data.ortho_patches[0].displacement_north, -0.061);
  EXPECT_EQ(data.ortho_patches[0].response, 0.99);
}

TEST(CollectTruth, AMalformedPatchRowNamesTheFileLineAndColumn) {
  TempFolder run;
  writeText(run.path() / "metrics.json", "{\"variant\": \"planar\", \"rgb_ate_m\": 0.5}\n");
  const auto patches = run.path() / "report" / "ortho_patches.csv";
  writeText(patches, "north_m,east_m,displacement_north_m,displacement_east_m,response\n1,2,3,4,5\n1,2,x,4,5\n");
  ReportData data;
  expectInputError([&] { collectTruth(run.path(), data); }, patches,
                   "line 3: column 'displacement_north_m': expected a number, got 'x'");
}

TEST(CollectTruth, WithoutMetricsItSaysHowToGetThem) {
  TempFolder run;
  ReportData data;
  collectTruth(run.path(), data);
  EXPECT_TRUE(data.metrics.empty());
  ASSERT_EQ(data.notes.size(), 1u);
  EXPECT_NE(data.notes[0].find("hsmap evaluate RUN --truth SURVEY/truth"), std::string::npos);
}

TEST(CollectTrajectory, FramesKeyframesAndLossesRoundTripFromTheRunFolder) {
  TempFolder run;
  std::vector<TimedPose> frames;
  for (int i = 0; i < 4; ++i) frames.push_back({100.0 + 0.5 * i, SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(i, -i, 2))});
  std::filesystem::create_directories(run.path() / "trajectory");
  writeTimedPoseTable(run.path() / "trajectory" / "frames.csv", frames);
  writeText(run.path() / "georef" / "keyframes.csv",
            "keyframe,frame,t,segment,x,y,z,qw,qx,qy,qz\n0,0,100,0,0,0,2,1,0,0,0\n1,3,101.5,0,3,-3,2,1,0,0,0\n");
  writeText(run.path() / "frontend" / "losses.csv", "first_frame,last_frame,reason\n1,2,too few corners\n");
  ReportData data;
  data.variant = "sequential";
  collectTrajectory(run.path(), nullptr, data);
  ASSERT_EQ(data.frames.size(), 4u);
  EXPECT_EQ(data.frames[3].north, 3.0);
  EXPECT_EQ(data.frames[3].east, -3.0);
  EXPECT_EQ(data.frames[3].down, 2.0);
  ASSERT_EQ(data.keyframes.size(), 2u);
  EXPECT_EQ(data.keyframes[1].t, 101.5);
  ASSERT_EQ(data.losses.size(), 1u);
  EXPECT_EQ(data.losses[0].reason, "too few corners");
  EXPECT_EQ(data.losses[0].t_first, 100.5);
  EXPECT_EQ(data.losses[0].t_last, 101.0);
  EXPECT_TRUE(data.notes.empty());
}

TEST(CollectTrajectory, AKeyframeTableWithoutPositionsNamesTheColumn) {
  TempFolder run;
  const auto keyframes = run.path() / "georef" / "keyframes.csv";
  writeText(keyframes, "keyframe,frame,t,segment\n0,0,100,0\n");
  ReportData data;
  expectInputError([&] { collectTrajectory(run.path(), nullptr, data); }, keyframes,
                   "line 1: expected a column 'x' in the header, got 'keyframe,frame,t,segment'");
}

TEST(ReadSpectralGrid, AveragesBlocksOverThePixelsWithData) {
  TempFolder folder;
  EnviHeader header;
  header.samples = 4;
  header.lines = 2;
  header.bands = 2;
  header.wavelength = {450, 550};
  header.wavelength_units = "Nanometers";
  const auto hdr = folder.path() / "ortho.hdr";
  {
    EnviWriter writer(hdr, header);
    // Band-major lines: band 0 then band 1, 4 samples each; NaN = no data.
    const float line0[] = {1, 3, 10, NAN, 2, 4, 20, NAN};
    const float line1[] = {5, 7, NAN, NAN, 6, 8, NAN, NAN};
    writer.writeLine(line0);
    writer.writeLine(line1);
    writer.finish();
  }
  const ReportSpectralGrid grid = readSpectralGrid(hdr, 2);  // at most 2 blocks: of 2 x 2 pixels
  ASSERT_EQ(grid.block_px, 2);
  ASSERT_EQ(grid.columns, 2);
  ASSERT_EQ(grid.rows, 1);
  EXPECT_EQ(grid.wavelengths_nm, (std::vector<double>{450, 550}));
  const auto value = [&](int block, int band) {
    const unsigned short q = grid.values[std::size_t(block * 2 + band)];
    return q == 65535 ? NAN : grid.offsets[std::size_t(band)] + grid.scales[std::size_t(band)] * q;
  };
  EXPECT_NEAR(value(0, 0), (1 + 3 + 5 + 7) / 4.0, 1e-3);
  EXPECT_NEAR(value(0, 1), (2 + 4 + 6 + 8) / 4.0, 1e-3);
  EXPECT_NEAR(value(1, 0), 10.0, 1e-3);  // the one pixel with data
  EXPECT_NEAR(value(1, 1), 20.0, 1e-3);
}

TEST(RasteriseMeshTopView, ShowsTheTopmostTriangleAndItsDepth) {
  PlyMesh mesh;
  // Two squares' worth of triangles over the same 1 x 1 m: one at down 5, one above it at down 4.
  mesh.vertices = {{0, 0, 5}, {1, 0, 5}, {1, 1, 5}, {0, 0, 4}, {1, 0, 4}, {0, 1, 4}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  const MeshTopView view = rasteriseMeshTopView(mesh, 100);
  EXPECT_NEAR(view.pixel_m, 0.01, 1e-12);
  EXPECT_EQ(view.image.cols, 100);
  EXPECT_EQ(view.image.rows, 100);
  EXPECT_NEAR(view.downAt(0.2, 0.1), 4.0, 1e-6);    // under both: the upper one
  EXPECT_NEAR(view.downAt(0.8, 0.7), 5.0, 1e-6);    // only the lower one
  EXPECT_TRUE(std::isnan(view.downAt(0.2, 0.9)));  // no triangle
  EXPECT_TRUE(std::isnan(view.downAt(5, 5)));      // outside
}

}  // namespace
}  // namespace hsmap
