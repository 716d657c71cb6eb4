// The hyperspectral point cloud of the tiny simulated survey, cast with the
// TRUE scan line poses onto the TRUE scene: points.ply reads back with the
// header it claims, every cell of the hits is one point with the mean of its
// hits (checked against a brute-force binning of the same casts), batches do
// not change a byte, NaN and ignore-value spectra are counted and left out.
#include "pipelines/products/hyperspectral_point_cloud.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <tuple>

#include "core/io/atomic_file.h"
#include "core/io/envi_reader.h"
#include "core/io/envi_writer.h"
#include "core/io/ply_io.h"
#include "core/util/input_error.h"
#include "pipelines/products/cell_release_map.h"
#include "pipelines/products/hyperspectral_point_cloud_ply.h"
#include "tests/support/tiny_products_fixture.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::tinyProductsSurvey;
using CellKey = std::tuple<std::int64_t, std::int64_t, std::int64_t>;

struct Setup {
  Survey survey = loadSurvey(tinyProductsSurvey().folder);
  PlyMesh ply = readPly(tinyProductsSurvey().scene_ply);
  MeshRayCaster mesh{ply.vertices, ply.triangles};
  PushbroomCamera camera{survey.config.uhi.camera};
};
const Setup& setup() {
  static const Setup* s = new Setup();
  return *s;
}

HyperspectralPointCloudReport writeCloud(const EnviReader& cube, const std::filesystem::path& ply,
                                         const HyperspectralPointCloudOptions& options = {}) {
  std::ostringstream log;
  return writeHyperspectralPointCloud(cube, setup().survey.wavelengths_nm, setup().camera,
                                      tinyProductsSurvey().true_line_poses, setup().mesh, setup().survey.origin, ply,
                                      options, log);
}

std::string fileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(HyperspectralPointCloud, ReadsBackWithItsHeaderAndMatchesABruteForceBinning) {
  testing::TempFolder folder;
  const std::filesystem::path path = folder.path() / "hyperspectral" / "points.ply";
  const EnviReader& cube = *setup().survey.cube;
  const HyperspectralPointCloudReport report = writeCloud(cube, path);
  std::cout << report.summary();
  ASSERT_TRUE(std::filesystem::is_regular_file(path));
  EXPECT_FALSE(std::filesystem::exists(AtomicFile::partialPathFor(path)));
  EXPECT_EQ(std::int64_t(std::filesystem::file_size(path)), report.bytes);

  const HyperspectralPointCloud cloud = readHyperspectralPointCloud(path);
  EXPECT_EQ(cloud.wavelengths_nm, setup().survey.wavelengths_nm);
  EXPECT_DOUBLE_EQ(cloud.cell_m, 0.02);
  ASSERT_EQ(std::int64_t(cloud.p_W.size()), report.points);
  EXPECT_GT(report.points, 100);
  EXPECT_EQ(report.skipped_non_finite + report.skipped_ignore_value, 0);
  EXPECT_EQ(report.binned, report.hits);
  EXPECT_EQ(report.early_released, 0);
  // A generic PLY reader (CGAL's, through readPly) reads the same vertices.
  const PlyMesh generic = readPly(path);
  ASSERT_EQ(generic.vertices.size(), cloud.p_W.size());
  EXPECT_TRUE(generic.vertices.front().isApprox(cloud.p_W.front(), 1e-12));
  EXPECT_TRUE(generic.vertices.back().isApprox(cloud.p_W.back(), 1e-12));

  // Brute force: every line cast and every hit binned in one map.
  const ScanLineCaster caster(setup().camera, setup().mesh);
  const int bands = cube.bands();
  std::map<CellKey, std::tuple<Eigen::Vector3d, int, std::vector<double>>> cells;
  ScanLineHits hits;
  Eigen::MatrixXf line;
  for (const LinePose& pose : tinyProductsSurvey().true_line_poses) {
    caster.castLine(pose.line, pose.T, hits);
    cube.readLine(int(pose.line), line);
    for (int s = 0; s < cube.samples(); ++s) {
      if (!hits.hit(s)) continue;
      const Eigen::Vector3d& p = hits.p_W[std::size_t(s)];
      auto& [sum_W, count, spectrum] = cells[{latticeIndex(p.x(), 0.02), latticeIndex(p.y(), 0.02),
                                              latticeIndex(p.z(), 0.02)}];
      if (count == 0) sum_W.setZero(), spectrum.assign(std::size_t(bands), 0.0);
      sum_W += p;
      ++count;
      for (int b = 0; b < bands; ++b) spectrum[std::size_t(b)] += line(b, s);
    }
  }
  ASSERT_EQ(cells.size(), cloud.p_W.size());  // one point a cell: none split, none duplicated
  std::int64_t hit_total = 0;
  for (std::size_t i = 0; i < cloud.p_W.size(); ++i) {
    const Eigen::Vector3d& p = cloud.p_W[i];
    const CellKey key{latticeIndex(p.x(), 0.02), latticeIndex(p.y(), 0.02), latticeIndex(p.z(), 0.02)};
    const auto it = cells.find(key);
    ASSERT_NE(it, cells.end()) << "point " << i << " in a cell without hits";
    const auto& [sum_W, count, spectrum] = it->second;
    ASSERT_EQ(int(cloud.hits[i]), count) << i;
    ASSERT_LT((p - sum_W / count).norm(), 1e-9) << i;
    for (int b = 0; b < bands; ++b) {
      const double mean = spectrum[std::size_t(b)] / count;
      ASSERT_NEAR(cloud.spectra[i * std::size_t(bands) + std::size_t(b)], mean, 1e-5 * std::abs(mean) + 1e-6)
          << i << " band " << b;
    }
    hit_total += count;
  }
  EXPECT_EQ(hit_total, report.hits);

  // Batches of 1 or 7 lines: the same file, byte for byte.
  for (int lines_per_batch : {1, 7}) {
    HyperspectralPointCloudOptions options;
    options.lines_per_batch = lines_per_batch;
    const std::filesystem::path other = folder.path() / ("batch" + std::to_string(lines_per_batch) + ".ply");
    writeCloud(cube, other, options);
    EXPECT_EQ(fileBytes(other), fileBytes(path)) << lines_per_batch << " lines a batch";
  }
}

TEST(HyperspectralPointCloud, LeavesOutAndCountsNaNAndIgnoreValueSpectra) {
  constexpr int kNanSample = 100, kIgnoreSample = 50;
  constexpr float kIgnoreValue = -1.0f;
  testing::TempFolder folder;
  const EnviReader& original = *setup().survey.cube;
  EnviHeader header = original.header();
  header.data_type = EnviDataType::float32;
  header.interleave = EnviInterleave::bil;
  header.byte_order = 0;
  header.header_offset = 0;
  header.other_fields.emplace_back("data ignore value", "-1");
  {
    EnviWriter writer(folder.path() / "cube.hdr", header);
    Eigen::MatrixXf line;
    for (int l = 0; l < original.lines(); ++l) {
      original.readLine(l, line);
      line(3, kNanSample) = std::numeric_limits<float>::quiet_NaN();
      line.col(kIgnoreSample).setConstant(kIgnoreValue);
      writer.writeLine(line);
    }
    writer.finish();
  }
  const EnviReader spoiled(folder.path() / "cube.hdr");
  const ScanLineCaster caster(setup().camera, setup().mesh);
  std::int64_t nan_hits = 0, ignore_hits = 0;
  ScanLineHits hits;
  for (const LinePose& pose : tinyProductsSurvey().true_line_poses) {
    caster.castLine(pose.line, pose.T, hits);
    nan_hits += hits.hit(kNanSample) ? 1 : 0;
    ignore_hits += hits.hit(kIgnoreSample) ? 1 : 0;
  }
  ASSERT_GT(nan_hits, 50);
  ASSERT_GT(ignore_hits, 50);

  const HyperspectralPointCloudReport report = writeCloud(spoiled, folder.path() / "points.ply");
  EXPECT_EQ(report.skipped_non_finite, nan_hits);
  EXPECT_EQ(report.skipped_ignore_value, ignore_hits);
  EXPECT_EQ(report.binned, report.hits - nan_hits - ignore_hits);
  const HyperspectralPointCloud cloud = readHyperspectralPointCloud(folder.path() / "points.ply");
  std::int64_t binned = 0;
  for (std::uint32_t h : cloud.hits) binned += h;
  EXPECT_EQ(binned, report.binned);
  for (float value : cloud.spectra) {
    ASSERT_TRUE(std::isfinite(value));
    ASSERT_NE(value, kIgnoreValue);  // an ignored spectrum is never averaged in (here all its bands are -1)
  }
}

TEST(HyperspectralPointCloud, RejectsABadCellSizeAndLeavesNoFile) {
  testing::TempFolder folder;
  HyperspectralPointCloudOptions options;
  for (double cell : {0.0, -0.02, 0.0005, 11.0, std::numeric_limits<double>::quiet_NaN()}) {
    options.cell_m = cell;
    EXPECT_THROW(options.validate(), std::invalid_argument) << cell;
    EXPECT_THROW(writeCloud(*setup().survey.cube, folder.path() / "points.ply", options), std::invalid_argument);
  }
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "points.ply"));
}

TEST(HyperspectralPointCloud, ATruncatedFileIsAnInputError) {
  testing::TempFolder folder;
  const std::filesystem::path path = folder.path() / "points.ply";
  writeCloud(*setup().survey.cube, path);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 10);
  EXPECT_THROW(readHyperspectralPointCloud(path), InputError);
}

}  // namespace
}  // namespace hsmap
