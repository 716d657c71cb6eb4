// OrthoTileAccumulator: the mean of the hits in a pixel, the nearest hit's
// ancillary values (a filled pixel's interpolated), gap filling only between
// observed pixels, tiles with a
// halo equal to one accumulator over the whole grid.
#include "pipelines/products/ortho_accumulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace hsmap {
namespace {

OrthoGrid smallGrid(int cols, int rows) {
  OrthoGrid grid;
  grid.pixel_m = 0.01;
  grid.west_m = 1000.0;
  grid.north_m = 2000.0;
  grid.cols = cols;
  grid.rows = rows;
  grid.zone = 31;
  return grid;
}

OrthoHit hitAt(double col, double row, const std::vector<float>& spectrum, float line = 0, float sample = 0) {
  OrthoHit hit;
  hit.col_row = Eigen::Vector2d(col, row);
  hit.spectrum = spectrum.data();
  hit.line = line;
  hit.sample = sample;
  hit.range_m = 1.5f;
  hit.incidence_deg = 10.0f;
  return hit;
}

TEST(OrthoTileAccumulator, PixelIsTheMeanOfItsHitsAndKeepsTheNearestHitsAncillary) {
  const OrthoGrid grid = smallGrid(5, 4);
  OrthoTileAccumulator tile(grid, 2, 0, 4, 0);
  const std::vector<float> a{1.0f, 10.0f}, b{3.0f, 30.0f};
  EXPECT_TRUE(tile.add(hitAt(2.3, 1.4, a, 7, 11)));
  EXPECT_TRUE(tile.add(hitAt(1.9, 0.9, b, 8, 12)));  // nearer the centre of (2, 1)
  EXPECT_FALSE(tile.add(hitAt(-0.6, 1.0, a)));      // outside the grid
  tile.finish(0);
  std::vector<float> row(2 * 5), ancillary(4 * 5);
  tile.spectraRow(1, row.data());
  EXPECT_FLOAT_EQ(row[0 * 5 + 2], 2.0f);
  EXPECT_FLOAT_EQ(row[1 * 5 + 2], 20.0f);
  EXPECT_TRUE(std::isnan(row[0 * 5 + 1]));
  tile.ancillaryRow(1, ancillary.data());
  EXPECT_FLOAT_EQ(ancillary[0 * 5 + 2], 8.0f);
  EXPECT_FLOAT_EQ(ancillary[1 * 5 + 2], 12.0f);
  EXPECT_FLOAT_EQ(ancillary[2 * 5 + 2], 1.5f);
  EXPECT_FLOAT_EQ(ancillary[3 * 5 + 2], 10.0f);
  EXPECT_TRUE(std::isnan(ancillary[0 * 5 + 3]));
  EXPECT_EQ(tile.observedPixels(), 1);
  EXPECT_EQ(tile.filledPixels(), 0);
}

TEST(OrthoTileAccumulator, FillsHolesBetweenObservedPixelsButNeverGrowsTheEdge) {
  // Observed columns 0 and 2 of every row; column 1 is a hole between them,
  // columns 3.. lie outside the swath.
  const OrthoGrid grid = smallGrid(6, 3);
  OrthoTileAccumulator tile(grid, 1, 0, 3, 1);
  const std::vector<float> left{2.0f}, right{4.0f};
  for (int r = 0; r < 3; ++r) {
    tile.add(hitAt(0, r, left));
    tile.add(hitAt(2, r, right));
  }
  tile.finish(2);
  std::vector<float> row(6);
  for (int r = 0; r < 3; ++r) {
    tile.spectraRow(r, row.data());
    EXPECT_FLOAT_EQ(row[1], 3.0f) << "row " << r;  // symmetric neighbours: their mean
    for (int c = 3; c < 6; ++c) EXPECT_TRUE(std::isnan(row[c])) << "row " << r << " col " << c;
  }
  EXPECT_EQ(tile.observedPixels(), 6);
  EXPECT_EQ(tile.filledPixels(), 3);
}

TEST(OrthoTileAccumulator, AFilledPixelsLineAndSampleLieBetweenItsSources) {
  // Scan lines along the rows: line 10 observed row 0, line 11 row 2; row 1
  // is the gap between them. Its line is 10.5 (not one of the two, which
  // would place the pixel a whole row off); farther east, two passes over
  // the spot (lines 10 and 500) do not average: the nearest source's values.
  const OrthoGrid grid = smallGrid(7, 3);
  OrthoTileAccumulator tile(grid, 1, 0, 3, 0);
  const std::vector<float> s{1.0f};
  for (int c = 0; c < 3; ++c) {
    tile.add(hitAt(c, 0, s, 10, 100 + c));
    tile.add(hitAt(c, 2, s, 11, 100 + c));
  }
  for (int c = 4; c < 7; ++c) {
    tile.add(hitAt(c, 0, s, 10, 100 + c));
    tile.add(hitAt(c, 2, s, 500, 900 + c));
  }
  tile.finish(1);
  // Row 1 but column 3 (no source in its cross), and column 3 of rows 0
  // and 2 (between columns 2 and 4).
  EXPECT_EQ(tile.filledPixels(), 8);
  std::vector<float> ancillary(4 * 7);
  tile.ancillaryRow(1, ancillary.data());
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(ancillary[0 * 7 + c], 10.5f) << "col " << c;
    EXPECT_FLOAT_EQ(ancillary[1 * 7 + c], 100.0f + c) << "col " << c;
    EXPECT_FLOAT_EQ(ancillary[2 * 7 + c], 1.5f) << "col " << c;
  }
  for (int c = 4; c < 7; ++c) {
    const float line = ancillary[0 * 7 + c];
    EXPECT_TRUE(line == 10.0f || line == 500.0f) << "col " << c << ": " << line;
  }
}

// Random hits on a 20 x 30 grid, accumulated once over the grid and in
// tiles of 7 rows with `halo`: the owned rows must be the same. With
// `max_reach` > 0 each hit reaches a random 0..max_reach pixels.
void expectTilesEqualOneAccumulator(int halo, int fill_radius, int max_reach) {
  const OrthoGrid grid = smallGrid(20, 30);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> col(-0.5, 19.5), row(-0.5, 29.5);
  std::uniform_real_distribution<float> reach(0.0f, float(max_reach));
  std::vector<std::vector<float>> spectra;
  std::vector<OrthoHit> hits;
  for (int i = 0; i < 250; ++i) spectra.push_back({float(i), float(2 * i)});
  for (int i = 0; i < 250; ++i) {
    hits.push_back(hitAt(col(rng), row(rng), spectra[std::size_t(i)]));
    if (max_reach > 0) hits.back().reach_px = reach(rng);
  }
  auto run = [&](int row_begin, int row_end, std::vector<float>& out) {
    OrthoTileAccumulator tile(grid, 2, row_begin, row_end, halo);
    for (const OrthoHit& hit : hits) tile.add(hit);
    tile.finish(fill_radius);
    std::vector<float> line(2 * 20);
    for (int r = row_begin; r < row_end; ++r) {
      tile.spectraRow(r, line.data());
      out.insert(out.end(), line.begin(), line.end());
    }
    return tile.filledPixels();
  };
  std::vector<float> whole, tiled;
  const auto filled_whole = run(0, 30, whole);
  std::int64_t filled_tiles = 0;
  for (int r = 0; r < 30; r += 7) filled_tiles += run(r, std::min(30, r + 7), tiled);
  ASSERT_EQ(whole.size(), tiled.size());
  EXPECT_GT(filled_whole, 0);
  EXPECT_EQ(filled_whole, filled_tiles);
  for (std::size_t i = 0; i < whole.size(); ++i) {
    if (std::isnan(whole[i])) {
      EXPECT_TRUE(std::isnan(tiled[i])) << i;
    } else {
      EXPECT_FLOAT_EQ(whole[i], tiled[i]) << i;
    }
  }
}

TEST(OrthoTileAccumulator, TilesWithAHaloEqualOneAccumulatorOverTheGrid) {
  expectTilesEqualOneAccumulator(2, 2, 0);
}

TEST(OrthoTileAccumulator, TilesWithAHaloEqualOneAccumulatorAlsoWhenHitsReachFartherThanTheRadius) {
  expectTilesEqualOneAccumulator(4, 1, 4);
}

TEST(OrthoTileAccumulator, AHitsOwnReachFillsTheWiderGapsOfFannedLinesAndNoFartherThanItReaches) {
  // Two "scan lines" along rows 0 and 5 (a turn's outer side, where the
  // lines lie 5 pixels apart) and two along rows 14 and 16 (2 apart, the
  // median spacing: fill radius 2). Rows 1-4 are filled only when the hits
  // of rows 0 and 5 reach 5 pixels. Rows 9-12 are out of every source's
  // reach (row 5's hits are at least sqrt(4^2 + 5^2) > 5 pixels from them
  // in the cones left and right; rows 14's are beyond 2), so stay empty;
  // row 15 is the median gap, filled either way.
  const OrthoGrid grid = smallGrid(10, 17);
  const std::vector<float> a{1.0f}, b{3.0f};
  for (const float reach : {0.0f, 5.0f}) {
    OrthoTileAccumulator tile(grid, 1, 0, 17, 5);
    for (int c = 0; c < 10; ++c) {
      OrthoHit top = hitAt(c, 0, a), fanned = hitAt(c, 5, b);
      top.reach_px = fanned.reach_px = reach;
      tile.add(top);
      tile.add(fanned);
      tile.add(hitAt(c, 14, a));
      tile.add(hitAt(c, 16, b));
    }
    tile.finish(2);
    std::vector<float> row(10);
    for (int r = 1; r <= 4; ++r) {
      tile.spectraRow(r, row.data());
      if (reach == 0.0f) {
        EXPECT_TRUE(std::isnan(row[5])) << "row " << r;
      } else {
        EXPECT_GT(row[5], 1.0f) << "row " << r;  // between the two lines' values
        EXPECT_LT(row[5], 3.0f) << "row " << r;
      }
    }
    for (int r = 9; r <= 12; ++r) {
      tile.spectraRow(r, row.data());
      for (int c = 0; c < 10; ++c) EXPECT_TRUE(std::isnan(row[c])) << "row " << r << ", reach " << reach;
    }
    tile.spectraRow(15, row.data());
    EXPECT_FLOAT_EQ(row[5], 2.0f);
  }
}

TEST(OrthoTileAccumulator, AReusedAccumulatorGivesTheSameBitsAsANewOne) {
  // reset() clears only counts and states: what an earlier tile left in the
  // sums and ancillary values must never show through.
  const OrthoGrid grid = smallGrid(12, 20);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> col(-0.5, 11.5), row(-0.5, 19.5);
  std::vector<std::vector<float>> spectra;
  std::vector<Eigen::Vector2d> where;
  for (int i = 0; i < 120; ++i) {
    spectra.push_back({float(i) + 0.5f, -float(3 * i)});
    where.emplace_back(col(rng), row(rng));
  }
  auto feed = [&](OrthoTileAccumulator& tile) {
    for (std::size_t i = 0; i < where.size(); ++i) {
      tile.add(hitAt(where[i].x(), where[i].y(), spectra[i], float(i), float(i % 7)));
    }
    tile.finish(2);
  };
  auto rows = [&](const OrthoTileAccumulator& tile, std::vector<float>& spectra_out,
                  std::vector<float>& ancillary_out) {
    std::vector<float> line(2 * 12), ancillary(4 * 12);
    for (int r = tile.rowBegin(); r < tile.rowEnd(); ++r) {
      tile.spectraRow(r, line.data());
      tile.ancillaryRow(r, ancillary.data());
      spectra_out.insert(spectra_out.end(), line.begin(), line.end());
      ancillary_out.insert(ancillary_out.end(), ancillary.begin(), ancillary.end());
    }
  };
  OrthoTileAccumulator fresh(grid, 2, 6, 14, 2);
  feed(fresh);
  // Dirty every pixel of a larger tile with other spectra, then reuse it.
  OrthoTileAccumulator reused(grid, 2, 0, 20, 2);
  const std::vector<float> junk{1e9f, -1e9f};
  for (int r = 0; r < 20; ++r) {
    for (int c = 0; c < 12; ++c) reused.add(hitAt(c + 0.3, r - 0.2, junk, 99, 99));
  }
  reused.finish(2);
  reused.reset(6, 14);
  feed(reused);
  std::vector<float> fresh_spectra, fresh_ancillary, reused_spectra, reused_ancillary;
  rows(fresh, fresh_spectra, fresh_ancillary);
  rows(reused, reused_spectra, reused_ancillary);
  ASSERT_EQ(fresh_spectra.size(), reused_spectra.size());
  EXPECT_EQ(0, std::memcmp(fresh_spectra.data(), reused_spectra.data(),
                           fresh_spectra.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(fresh_ancillary.data(), reused_ancillary.data(),
                           fresh_ancillary.size() * sizeof(float)));
  EXPECT_EQ(fresh.observedPixels(), reused.observedPixels());
  EXPECT_EQ(fresh.filledPixels(), reused.filledPixels());
  EXPECT_GT(fresh.filledPixels(), 0);
}

}  // namespace
}  // namespace hsmap
