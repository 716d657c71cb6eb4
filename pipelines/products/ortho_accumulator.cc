#include "pipelines/products/ortho_accumulator.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <new>

#include <sys/mman.h>

#include <tbb/parallel_for.h>

#include "core/io/float_transpose.h"
#include "pipelines/products/weighted_spectrum_sum.h"

namespace hsmap {

namespace {
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr std::size_t kHugePage = std::size_t(2) << 20;
}  // namespace

void OrthoTileAccumulator::FreeDeleter::operator()(float* p) const { std::free(p); }

std::int64_t OrthoTileAccumulator::bytesPerRow(int cols, int bands) {
  return std::int64_t(cols) * (std::int64_t(bands) * 4 + 4 + 1 + 1 + 4 + 4 + 16);
}

OrthoTileAccumulator::OrthoTileAccumulator(const OrthoGrid& grid, int bands, int row_begin,
                                           int row_end, int halo)
    : rows_(grid.rows), cols_(grid.cols), bands_(bands), halo_(halo) {
  if (bands <= 0 || halo < 0 || halo > kMaxReachPx || grid.cols <= 0) {
    throw std::invalid_argument("OrthoTileAccumulator: " + std::to_string(bands) + " bands, " +
                                std::to_string(grid.cols) + " columns, halo " + std::to_string(halo));
  }
  reset(row_begin, row_end);
}

void OrthoTileAccumulator::reset(int row_begin, int row_end) {
  if (row_begin < 0 || row_end > rows_ || row_begin >= row_end) {
    throw std::invalid_argument("OrthoTileAccumulator: rows [" + std::to_string(row_begin) + ", " +
                                std::to_string(row_end) + ") of a grid of " + std::to_string(rows_));
  }
  row_begin_ = row_begin;
  row_end_ = row_end;
  first_row_ = std::max(0, row_begin - halo_);
  last_row_ = std::min(rows_, row_end + halo_);
  finished_ = false;
  observed_owned_ = filled_owned_ = 0;
  max_reach_px_ = 0;
  const std::size_t pixels = std::size_t(last_row_ - first_row_) * std::size_t(cols_);
  // Only the counts and states are cleared (5 bytes a pixel): a pixel's sums,
  // best distance and ancillary values are set by its first hit (add) or by
  // the filling, and never read while its count is 0 and it is not filled.
  // Clearing all of them (~870 bytes a pixel at 211 bands) cost as much as
  // the accumulation. resize() keeps the capacity when the new size fits.
  const std::size_t floats = pixels * std::size_t(bands_);
  if (floats > sums_capacity_) {
    const std::size_t bytes = (floats * sizeof(float) + kHugePage - 1) / kHugePage * kHugePage;
    sums_.reset(static_cast<float*>(std::aligned_alloc(kHugePage, bytes)));
    if (!sums_) throw std::bad_alloc();
    sums_capacity_ = bytes / sizeof(float);
#if defined(MADV_HUGEPAGE)
    ::madvise(sums_.get(), bytes, MADV_HUGEPAGE);  // a hint: without it, 4 KB pages
#endif
  }
  counts_.assign(pixels, 0);
  state_.assign(pixels, kEmpty);
  best_d2_.resize(pixels);
  mean_scale_.resize(pixels);
  reach_px_.resize(pixels);
  ancillary_.resize(pixels);
}

bool OrthoTileAccumulator::owns(const Eigen::Vector2d& col_row) const {
  const double row = std::floor(col_row.y() + 0.5);
  return row >= row_begin_ && row < row_end_;
}

bool OrthoTileAccumulator::add(const OrthoHit& hit) {
  const double col_f = std::floor(hit.col_row.x() + 0.5);
  const double row_f = std::floor(hit.col_row.y() + 0.5);
  if (!(col_f >= 0 && col_f < cols_ && row_f >= first_row_ && row_f < last_row_)) return false;
  const int col = int(col_f), row = int(row_f);
  const std::size_t i = index(row, col);
  float* sum = &sums_[i * std::size_t(bands_)];
  const float d2 = float((hit.col_row.x() - col_f) * (hit.col_row.x() - col_f) +
                         (hit.col_row.y() - row_f) * (hit.col_row.y() - row_f));
  // The hit's reach in whole pixels, at most the halo (so that a tile fills
  // as one accumulator over the grid would).
  const std::uint8_t reach = std::uint8_t(
      hit.reach_px > 0.0f ? std::min(float(halo_), std::ceil(hit.reach_px - 1e-4f)) : 0.0f);
  max_reach_px_ = std::max(max_reach_px_, int(reach));
  if (counts_[i] == 0) {
    // 0 + x, not x: the same bits as adding to a cleared sum (-0 becomes +0).
    for (int b = 0; b < bands_; ++b) sum[b] = 0.0f + hit.spectrum[b];
    counts_[i] = 1;
    best_d2_[i] = d2;
    reach_px_[i] = reach;
    ancillary_[i] = Eigen::Vector4f(hit.line, hit.sample, hit.range_m, hit.incidence_deg);
    return row >= row_begin_ && row < row_end_;
  }
  for (int b = 0; b < bands_; ++b) sum[b] += hit.spectrum[b];
  ++counts_[i];
  reach_px_[i] = std::max(reach_px_[i], reach);
  if (d2 < best_d2_[i]) {
    best_d2_[i] = d2;
    ancillary_[i] = Eigen::Vector4f(hit.line, hit.sample, hit.range_m, hit.incidence_deg);
  }
  return row >= row_begin_ && row < row_end_;
}

Eigen::Vector4f OrthoTileAccumulator::filledAncillary(
    const std::vector<std::pair<std::size_t, float>>& sources, float weight_sum,
    std::size_t nearest) const {
  // Interpolated like the spectrum: the pixel lies between its sources, so
  // its line and sample do too. Any one source's values instead would place
  // it a whole pixel off (and the nearest of two at equal distance is
  // whichever the scan meets first: always the same side, a bias).
  // Sources from different passes over the spot (lines far apart) do not
  // interpolate: then the nearest source's values.
  float line_min = std::numeric_limits<float>::infinity(), line_max = -line_min;
  Eigen::Vector4f mean = Eigen::Vector4f::Zero();
  for (const auto& [j, weight] : sources) {
    line_min = std::min(line_min, ancillary_[j][0]);
    line_max = std::max(line_max, ancillary_[j][0]);
    mean += weight * ancillary_[j];
  }
  if (line_max - line_min > kMaxInterpolatedLineSpan) return ancillary_[nearest];
  return mean / weight_sum;
}

void OrthoTileAccumulator::finish(int fill_radius_px) {
  if (finished_) throw std::logic_error("OrthoTileAccumulator::finish called twice");
  finished_ = true;
  const int rows = last_row_ - first_row_;
  // Observed pixels (every accumulated row: the halo feeds the filling), and
  // each row's span of observed columns (to skip the empty grid beside the
  // swath). The sums stay sums: an observed pixel's mean is sum * (1 /
  // count), taken where it is read (the filling, spectraRow) with the factor
  // kept here, which saves a pass over all sums (~1 KB a pixel) and gives
  // the same bits. Other pixels keep a factor of 1 (a filled pixel's sums
  // are its value).
  std::vector<int> observed_first(std::size_t(rows), cols_), observed_last(std::size_t(rows), -1);
  tbb::parallel_for(0, rows, [&](int r) {
    for (int c = 0; c < cols_; ++c) {
      const std::size_t i = std::size_t(r) * cols_ + c;
      mean_scale_[i] = counts_[i] == 0 ? 1.0f : 1.0f / float(counts_[i]);
      if (counts_[i] == 0) continue;
      state_[i] = kObserved;
      observed_first[std::size_t(r)] = std::min(observed_first[std::size_t(r)], c);
      observed_last[std::size_t(r)] = c;
    }
  });

  // Gap filling of the owned rows from observed pixels only (see the header).
  struct Offset {
    int dc, dr;
    float weight, d2;
  };
  std::vector<Offset> offsets;
  // Every source reaches at least fill_radius_px, and as far as its own
  // reach (the scan lines' local spacing, add()).
  const int min_reach = std::max(0, fill_radius_px);
  const float min_reach2 = float(min_reach * min_reach);
  const int radius = std::max(min_reach, max_reach_px_);
  for (int dr = -radius; dr <= radius; ++dr) {
    for (int dc = -radius; dc <= radius; ++dc) {
      const int d2 = dr * dr + dc * dc;
      if (d2 == 0 || d2 > radius * radius) continue;
      offsets.push_back({dc, dr, 1.0f / float(d2), float(d2)});
    }
  }
  std::vector<std::int64_t> filled_per_row(std::size_t(row_end_ - row_begin_), 0);
  std::vector<std::int64_t> observed_per_row(std::size_t(row_end_ - row_begin_), 0);
  // Marked apart and merged after the loop, so that rows filled in parallel
  // read a state_ nobody writes (sources are tested by state_ == kObserved).
  std::vector<std::uint8_t> filled_mark(state_.size(), 0);
  tbb::parallel_for(row_begin_, row_end_, [&](int row) {
    std::vector<std::pair<std::size_t, float>> sources;
    std::vector<const float*> source_spectra;
    std::vector<float> source_weights, source_scales;
    std::int64_t filled = 0, observed = 0;
    // Columns within `radius` of an observed pixel of the rows in reach.
    int col_begin = cols_, col_end = -1;
    for (int r = std::max(first_row_, row - radius); r < std::min(last_row_, row + radius + 1); ++r) {
      col_begin = std::min(col_begin, observed_first[std::size_t(r - first_row_)] - radius);
      col_end = std::max(col_end, observed_last[std::size_t(r - first_row_)] + radius);
    }
    col_begin = std::max(0, col_begin);
    col_end = std::min(cols_ - 1, col_end);
    for (int col = 0; col < cols_; ++col) {
      const std::size_t i = index(row, col);
      if (state_[i] == kObserved) {
        ++observed;
        continue;
      }
      if (offsets.empty() || col < col_begin || col > col_end) continue;
      bool left = false, right = false, up = false, down = false;
      float weight_sum = 0.0f, nearest_d2 = std::numeric_limits<float>::infinity();
      std::size_t nearest = 0;
      sources.clear();
      for (const Offset& o : offsets) {
        const int r = row + o.dr, c = col + o.dc;
        if (r < first_row_ || r >= last_row_ || c < 0 || c >= cols_) continue;
        const std::size_t j = index(r, c);
        if (state_[j] != kObserved) continue;
        if (o.d2 > min_reach2 && o.d2 > float(reach_px_[j]) * float(reach_px_[j])) continue;
        // Strict cones around the four axes (diagonals belong to none), so
        // that a straight or convex swath edge never has sources in two
        // opposite cones.
        left |= o.dc < 0 && -o.dc > std::abs(o.dr);
        right |= o.dc > 0 && o.dc > std::abs(o.dr);
        up |= o.dr < 0 && -o.dr > std::abs(o.dc);
        down |= o.dr > 0 && o.dr > std::abs(o.dc);
        sources.emplace_back(j, o.weight);
        weight_sum += o.weight;
        if (o.d2 < nearest_d2) {
          nearest_d2 = o.d2;
          nearest = j;
        }
      }
      if (!((left && right) || (up && down))) continue;
      source_spectra.clear();
      source_weights.clear();
      source_scales.clear();
      for (const auto& [j, weight] : sources) {
        source_spectra.push_back(&sums_[j * std::size_t(bands_)]);
        source_weights.push_back(weight);
        source_scales.push_back(mean_scale_[j]);
      }
      // The target is empty, so none of its sources: its sums can take the mix.
      float* target = &sums_[i * std::size_t(bands_)];
      weightedSpectrumSum(source_spectra.data(), source_weights.data(), source_scales.data(),
                          int(sources.size()), bands_, target);
      for (int b = 0; b < bands_; ++b) target[b] /= weight_sum;
      filled_mark[i] = 1;
      ancillary_[i] = filledAncillary(sources, weight_sum, nearest);
      ++filled;
    }
    filled_per_row[std::size_t(row - row_begin_)] = filled;
    observed_per_row[std::size_t(row - row_begin_)] = observed;
  });
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (filled_mark[i] != 0) state_[i] = kFilled;
  }
  for (std::size_t r = 0; r < filled_per_row.size(); ++r) {
    filled_owned_ += filled_per_row[r];
    observed_owned_ += observed_per_row[r];
  }
}

void OrthoTileAccumulator::spectraRow(int row, float* out) const {
  if (!finished_ || row < row_begin_ || row >= row_end_) {
    throw std::logic_error("OrthoTileAccumulator::spectraRow: row " + std::to_string(row) +
                           " not owned or not finished");
  }
  // A blocked transpose of the row's span of seen pixels that turns the
  // observed pixels' sums into means on the way (filled pixels hold their
  // value: scale 1), then NaN beside the span and over the empty pixels
  // inside it (their sums are stale or uninitialised). A strided copy pixel
  // by pixel cost the write thread more than the disk, and so did
  // transposing the empty grid beside the swath.
  const std::size_t first = index(row, 0);
  const std::uint8_t* state = &state_[first];
  int begin = 0, end = cols_;
  while (begin < end && state[begin] == kEmpty) ++begin;
  while (end > begin && state[end - 1] == kEmpty) --end;
  for (int b = 0; b < bands_; ++b) {
    float* band = out + std::size_t(b) * cols_;
    std::fill(band, band + begin, kNaNf);
    std::fill(band + end, band + cols_, kNaNf);
  }
  if (begin == end) return;
  transposeScaledRows(&sums_[(first + begin) * std::size_t(bands_)], std::size_t(end - begin),
                      std::size_t(bands_), std::size_t(bands_), &mean_scale_[first + begin], out + begin,
                      std::size_t(cols_));
  for (int col = begin; col < end; ++col) {
    if (state[col] != kEmpty) continue;
    for (int b = 0; b < bands_; ++b) out[std::size_t(b) * cols_ + col] = kNaNf;
  }
}

void OrthoTileAccumulator::ancillaryRow(int row, float* out) const {
  if (!finished_ || row < row_begin_ || row >= row_end_) {
    throw std::logic_error("OrthoTileAccumulator::ancillaryRow: row " + std::to_string(row) +
                           " not owned or not finished");
  }
  for (int col = 0; col < cols_; ++col) {
    const std::size_t i = index(row, col);
    for (int b = 0; b < 4; ++b) {
      out[std::size_t(b) * cols_ + col] = state_[i] == kEmpty ? kNaNf : ancillary_[i][b];
    }
  }
}

}  // namespace hsmap
