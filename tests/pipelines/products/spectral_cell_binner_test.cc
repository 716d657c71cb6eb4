// SpectralCellBinner: hits binned into cubes give one
// point a cube at the mean position with the mean spectrum, written once the
// survey has passed it, never split or duplicated across releases, and the
// pending cells stay under their bound.
#include "pipelines/products/spectral_cell_binner.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "pipelines/products/cell_release_map.h"

namespace hsmap {
namespace {

constexpr int kBands = 5;
constexpr double kCell = 0.02;

struct Emitted {
  Eigen::Vector3d p_W;
  std::uint32_t hits;
  std::vector<float> spectrum;
  std::int64_t after_sequence;  // the last sequence released when it was written
};

using CellKey = std::tuple<std::int64_t, std::int64_t, std::int64_t>;
CellKey keyOf(const Eigen::Vector3d& p) {
  return {latticeIndex(p.x(), kCell), latticeIndex(p.y(), kCell), latticeIndex(p.z(), kCell)};
}

Eigen::AlignedBox2d box(double x0, double y0, double x1, double y1) {
  return Eigen::AlignedBox2d(Eigen::Vector2d(x0, y0), Eigen::Vector2d(x1, y1));
}

class BinnerTest : public ::testing::Test {
 protected:
  std::vector<Emitted> emitted;
  std::int64_t released = -1;
  CellSink sink() {
    return [this](const CellPoint& p) {
      emitted.push_back({p.p_W, p.hits, std::vector<float>(p.spectrum, p.spectrum + kBands), released});
    };
  }
};

TEST_F(BinnerTest, HitsOnAPlaneGivePointsOnThePlaneWithTheMeanSpectrum) {
  // 40 "lines" across a 0.3 m square on the plane z = 1.2345; every hit's
  // spectrum is known, so each cell's mean can be computed apart.
  const int lines = 40;
  std::vector<Eigen::AlignedBox2d> boxes;
  std::vector<std::vector<Eigen::Vector3d>> hits(lines);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, 0.3);
  for (int l = 0; l < lines; ++l) {
    Eigen::AlignedBox2d b;
    for (int s = 0; s < 200; ++s) {
      hits[l].emplace_back(u(random), u(random), 1.2345);
      b.extend(hits[l].back().head<2>());
    }
    boxes.push_back(b);
  }
  const CellReleaseMap releases(kCell, boxes);
  SpectralCellBinner binner(releases, kBands, std::int64_t(64) << 20, sink());
  std::map<CellKey, std::pair<std::vector<double>, int>> expected;  // sums, count
  for (int l = 0; l < lines; ++l) {
    for (std::size_t s = 0; s < hits[l].size(); ++s) {
      float spectrum[kBands];
      for (int b = 0; b < kBands; ++b) spectrum[b] = float(l + 0.5 * s + 10 * b);
      binner.add(hits[l][s], spectrum);
      auto& [sums, count] = expected[keyOf(hits[l][s])];
      sums.resize(kBands);
      for (int b = 0; b < kBands; ++b) sums[std::size_t(b)] += spectrum[b];
      ++count;
    }
    released = l;
    binner.releaseThrough(l);
  }
  binner.releaseAll();
  ASSERT_EQ(emitted.size(), expected.size());
  EXPECT_EQ(binner.emitted(), std::int64_t(expected.size()));
  EXPECT_EQ(binner.pendingCells(), 0);
  EXPECT_EQ(binner.earlyReleased(), 0);
  std::map<CellKey, int> seen;
  for (const Emitted& e : emitted) {
    EXPECT_NEAR(e.p_W.z(), 1.2345, 1e-12);
    const CellKey key = keyOf(e.p_W);  // the mean of a cell's hits lies in the cell
    ASSERT_EQ(++seen[key], 1) << "a cell written twice";
    const auto& [sums, count] = expected.at(key);
    EXPECT_EQ(int(e.hits), count);
    for (int b = 0; b < kBands; ++b) EXPECT_NEAR(e.spectrum[std::size_t(b)], sums[std::size_t(b)] / count, 1e-3);
  }
}

TEST_F(BinnerTest, ACellStraddlingAReleaseIsWrittenOnceWithAllItsHits) {
  // Lines 0..5: line 0 and line 5 both reach column A (x ~ 0.01); lines
  // 1..4 only reach column B (x ~ 3). Column A's cell gets a hit from line 0
  // and one from line 5: it must wait for line 5, while line 1's cell in B is
  // written as soon as line 4 (B's last line) is released.
  const std::vector<Eigen::AlignedBox2d> boxes = {box(0, 0, 0.05, 0.05), box(3, 0, 3.05, 0.05),
                                                  box(3, 0, 3.05, 0.05), box(3, 0, 3.05, 0.05),
                                                  box(3, 0, 3.05, 0.05), box(0, 0, 0.05, 0.05)};
  const CellReleaseMap releases(kCell, boxes);
  SpectralCellBinner binner(releases, kBands, std::int64_t(1) << 20, sink());
  const float one[kBands] = {1, 1, 1, 1, 1}, three[kBands] = {3, 3, 3, 3, 3};
  for (int l = 0; l < 6; ++l) {
    if (l == 0) binner.add(Eigen::Vector3d(0.011, 0.011, 2.001), one);
    if (l == 5) binner.add(Eigen::Vector3d(0.019, 0.019, 2.019), three);
    if (l >= 1 && l <= 4) binner.add(Eigen::Vector3d(3.01, 0.01, 2.0), one);
    released = l;
    binner.releaseThrough(l);
    if (l == 4) {
      ASSERT_EQ(emitted.size(), 1u);  // column B is done, column A is not
      EXPECT_EQ(emitted[0].hits, 4u);
      EXPECT_EQ(emitted[0].after_sequence, 4);
    }
  }
  ASSERT_EQ(emitted.size(), 2u);
  EXPECT_EQ(emitted[1].hits, 2u);
  EXPECT_EQ(emitted[1].after_sequence, 5);
  EXPECT_TRUE(emitted[1].p_W.isApprox(Eigen::Vector3d(0.015, 0.015, 2.010), 1e-12));
  EXPECT_FLOAT_EQ(emitted[1].spectrum[0], 2.0f);
  EXPECT_EQ(binner.pendingCells(), 0);
}

TEST_F(BinnerTest, PendingCellsStayUnderTheirBoundAndEarlyWritesAreCounted) {
  // One box over everything, released only at the end (a survey that comes
  // back over its ground): without the bound every cell would stay pending.
  const int lines = 10;
  std::vector<Eigen::AlignedBox2d> boxes(lines, box(0, 0, 1, 1));
  const CellReleaseMap releases(kCell, boxes);
  const std::int64_t bound_cells = 100;
  SpectralCellBinner binner(releases, kBands, bound_cells * SpectralCellBinner::bytesPerCell(kBands), sink());
  const float spectrum[kBands] = {1, 2, 3, 4, 5};
  std::int64_t added = 0;
  for (int l = 0; l < lines; ++l) {
    for (int i = 0; i < 50; ++i) {
      binner.add(Eigen::Vector3d(0.02 * i + 0.01, 0.02 * l + 0.01, 1.0), spectrum);
      ++added;
      ASSERT_LE(binner.pendingCells(), bound_cells);
    }
    binner.releaseThrough(l);
  }
  binner.releaseAll();
  EXPECT_GT(binner.earlyReleased(), 0);
  EXPECT_LE(binner.peakPendingCells(), bound_cells + 1);
  std::int64_t hits = 0;
  for (const Emitted& e : emitted) hits += e.hits;
  EXPECT_EQ(hits, added);  // nothing lost
}

}  // namespace
}  // namespace hsmap
