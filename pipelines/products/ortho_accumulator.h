#pragma once
// OrthoTileAccumulator: the spectra of one tile of the ortho-image (a band of
// whole grid rows), accumulated from scan-line hits, averaged and gap-filled.
//
// Accumulation. A pixel of a scan line whose ray hit the surface at p_W adds
// its spectrum to the ortho pixel CONTAINING the hit (OrthoGrid). The value
// of an ortho pixel is the MEAN of the spectra that landed in it (every hit
// weighs the same: no footprint model, no distance weighting), so spectra
// are never mixed with pixels they did not fall in.
//
// Ancillary per pixel (ancillary.hdr, 4 bands): scan line, sample, range (m)
// and incidence (deg) of the hit NEAREST the pixel centre (ties: the first
// added, i.e. the earlier line).
//
// Gap filling (finish()). At 5 mm pixels the hits of a survey are sparser
// than the grid (line spacing ~1 cm at 0.3 m/s and 30 lines/s), so many
// pixels inside the swath get no hit. An empty pixel is filled by inverse
// distance weighting (weights 1 / d^2, d in pixels between centres) of the
// OBSERVED pixels (those that got hits; filled pixels never feed others)
// within reach, and only when those pixels surround it: there are
// observed pixels in two opposite ones of the four strict cones around the
// axes (left and right: |dc| > |dr|; above and below: |dr| > |dc|; exact
// diagonals count in none). Holes between lines and samples are closed,
// and nothing is invented farther than the reach. Beside an edge of the
// swath the sources lie in one half-plane: they meet two opposite cones
// only as a run along the edge, k pixels out needing sources more than k
// pixels along it on both sides, within reach r: k < r / sqrt(2) (1 pixel
// for r = 3 beside an edge along a row or a column).
// An observed pixel reaches `fill_radius_px` (set from the median line
// spacing by the caller) or, when farther, its own reach: the largest
// OrthoHit::reach_px of its hits (the local line spacing: where the
// vehicle turns, the lines fan out on the outer side of the turn and their
// gaps are wider than the median spacing), at most the halo. The caller
// leaves the reach at 0 near the swath's sides (hyperspectral_ortho.cc), so
// that the sides grow no more than the median radius lets them. A filled
// pixel's ancillary values are interpolated with the same weights (a line between two lines is
// fractional), unless its sources' lines lie more than
// kMaxInterpolatedLineSpan apart (two passes over the spot): then those of
// the nearest source. Pixels still empty stay NaN (spectrum and ancillary).
//
// Tiles and halo. The tile owns grid rows [row_begin, row_end) and also
// accumulates `halo` rows above and below them, so that filling near its
// edges sees the same neighbours as anywhere else; a caller feeding every
// line that reaches [row_begin - halo, row_end + halo) gets, for the owned
// rows, exactly what one accumulator over the whole grid would give.
//
// Memory: bands * 4 + 30 bytes per pixel of (rows + 2 halo) x cols. The
// sums (nearly all of it) are allocated once, uninitialised, in transparent
// huge pages where the kernel allows (madvise): on the project's virtual
// machine a 4 KB page fault costs ~30 us, so first touching 256 MB page by
// page took 2-5 s, more than accumulating into it. reset() clears only the
// counts and states; a pixel's sums, nearest distance, reach and ancillary
// values are written by its first hit (so stale values of an earlier tile are never
// read: a reused accumulator gives the same bits as a new one).

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "pipelines/products/ortho_grid.h"

namespace hsmap {

// One hit to add: continuous pixel coordinates of p_W (OrthoGrid::pixelOfUtm),
// its spectrum (`bands` contiguous floats), and its ancillary values.
struct OrthoHit {
  Eigen::Vector2d col_row;
  const float* spectrum = nullptr;
  float line = 0, sample = 0, range_m = 0, incidence_deg = 0;
  // How far (grid pixels) the scan lines' own sampling spreads around this
  // hit: the distance to where the neighbouring lines' pixels of the same
  // sample fall (0: only finish()'s fill_radius_px). See "Gap filling".
  float reach_px = 0.0f;
};

class OrthoTileAccumulator {
 public:
  // Largest halo (and so reach) in pixels: reaches are kept in one byte.
  static constexpr int kMaxReachPx = 255;

  // A filled pixel's ancillary values are interpolated from sources whose
  // scan lines lie at most this far apart (one pass over the spot).
  static constexpr float kMaxInterpolatedLineSpan = 4.0f;

  // std::invalid_argument for an empty row range or one outside the grid,
  // non-positive bands or a halo outside [0, kMaxReachPx].
  OrthoTileAccumulator(const OrthoGrid& grid, int bands, int row_begin, int row_end, int halo);

  // Starts over on owned rows [row_begin, row_end) (same grid, bands and
  // halo), keeping the buffers: a stage that runs tile after tile allocates
  // (and the kernel maps) the memory once, not once per tile, which on the
  // project's virtual machine costs more than the accumulation itself.
  void reset(int row_begin, int row_end);

  int rowBegin() const { return row_begin_; }
  int rowEnd() const { return row_end_; }
  // Rows the tile accumulates: owned rows plus the halo, clipped to the grid.
  int firstRow() const { return first_row_; }
  int lastRow() const { return last_row_; }  // exclusive

  // Adds a hit if its pixel lies in [firstRow(), lastRow()) and inside the
  // grid's columns; returns whether the pixel is one of the OWNED rows (so
  // the caller can count every hit once over all tiles). Not thread-safe.
  bool add(const OrthoHit& hit);
  // Whether a pixel position lies in the owned rows.
  bool owns(const Eigen::Vector2d& col_row) const;

  // Gap filling (see above). Call once, after the last add(). The sums stay
  // sums: an observed pixel's mean (sum / count) is taken where it is read,
  // by the filling and by spectraRow(), which saves a pass over them all.
  void finish(int fill_radius_px);

  // After finish(): owned row `row` band-major, out[b * cols + c] (bands x
  // cols floats), NaN where empty: the layout of an ENVI line.
  void spectraRow(int row, float* out) const;
  // After finish(): owned row `row` of the 4 ancillary bands (4 x cols).
  void ancillaryRow(int row, float* out) const;

  // Over the owned rows, after finish().
  std::int64_t observedPixels() const { return observed_owned_; }
  std::int64_t filledPixels() const { return filled_owned_; }

  // Bytes a tile of `rows` rows (halo included) takes.
  static std::int64_t bytesPerRow(int cols, int bands);

 private:
  enum : std::uint8_t { kEmpty = 0, kObserved = 1, kFilled = 2 };
  Eigen::Vector4f filledAncillary(const std::vector<std::pair<std::size_t, float>>& sources,
                                  float weight_sum, std::size_t nearest) const;
  std::size_t index(int row, int col) const {
    return std::size_t(row - first_row_) * std::size_t(cols_) + std::size_t(col);
  }

  int rows_, cols_, bands_, halo_, row_begin_ = 0, row_end_ = 0, first_row_ = 0, last_row_ = 0;
  bool finished_ = false;
  struct FreeDeleter {
    void operator()(float* p) const;
  };
  std::unique_ptr<float[], FreeDeleter> sums_;  // pixel-major: [pixel * bands + b]
  std::size_t sums_capacity_ = 0;               // floats
  std::vector<std::uint32_t> counts_;
  std::vector<std::uint8_t> state_;
  std::vector<float> best_d2_;          // squared distance (px^2) of the nearest hit to the centre
  std::vector<float> mean_scale_;       // after finish(): 1 / count where observed, else 1
  std::vector<std::uint8_t> reach_px_;  // largest reach of the pixel's hits (whole pixels)
  int max_reach_px_ = 0;                // over the tile's hits
  std::vector<Eigen::Vector4f> ancillary_;  // line, sample, range, incidence
  std::int64_t observed_owned_ = 0, filled_owned_ = 0;
};

}  // namespace hsmap
