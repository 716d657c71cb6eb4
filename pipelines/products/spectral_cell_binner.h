#pragma once
// SpectralCellBinner: the hits of a hyperspectral survey binned into a 3-D
// lattice of cubes of side c in W (cell_release_map.h); a cell's point is
// the MEAN position and the MEAN spectrum of the hits that fell in it, with
// their number. Every hit weighs the same, as in an ortho pixel
// (ortho_accumulator.h): spectra are never mixed with cells they did not
// fall in.
//
// Streaming. Hits arrive scan line by scan line, in processing order
// (sequence 0, 1, ...). A cell is created by its first hit with the release
// sequence of its column (CellReleaseMap) and emitted by releaseThrough(s)
// once s reaches it: no later hit can land in it, so a cell is never split
// into two points nor written twice, however its hits are spread over
// batches. Pending cells are the ground the survey has not yet left: a few
// metres of swath on a straight track, whatever its length.
//
// Bounded memory whatever the survey: a survey that comes back over old
// ground keeps that ground pending; when the pending cells would take more
// than `max_pending_bytes`, the cells nearest their release are emitted
// early (counted by earlyReleased()), down to 3/4 of the bound. A later hit
// in such a cell starts a new point there (the only case where a cell gives
// two points).
//
// Determinism: sums are in the order of add(); points are emitted in the
// order (release sequence, creation), so the output does not depend on
// threads. Spectra are summed in float (as the ortho-image), positions in
// double. Not thread-safe.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <queue>
#include <unordered_map>
#include <vector>

#include "pipelines/products/cell_release_map.h"

namespace hsmap {

// One emitted point: valid only during the sink call.
struct CellPoint {
  Eigen::Vector3d p_W;              // mean of the hits
  std::uint32_t hits = 0;
  const float* spectrum = nullptr;  // `bands` means
};
using CellSink = std::function<void(const CellPoint&)>;

class SpectralCellBinner {
 public:
  // Keeps a reference to `releases` (it must outlive the binner).
  // std::invalid_argument for bands < 1 or a bound below one cell.
  SpectralCellBinner(const CellReleaseMap& releases, int bands, std::int64_t max_pending_bytes, CellSink sink);

  // Adds a hit at p_W (finite) with `bands` floats (the caller has checked
  // them). May emit cells early when the bound is reached.
  void add(const Eigen::Vector3d& p_W, const float* spectrum);
  // Emits every pending cell whose release sequence is <= `sequence`.
  void releaseThrough(std::int64_t sequence);
  // Emits every pending cell (the end of the survey).
  void releaseAll();

  std::int64_t pendingCells() const { return std::int64_t(cells_.size()); }
  std::int64_t peakPendingCells() const { return peak_pending_; }
  std::int64_t added() const { return added_; }
  std::int64_t emitted() const { return emitted_; }
  std::int64_t earlyReleased() const { return early_; }
  // What a pending cell costs (its sums, its key and the bookkeeping).
  static std::int64_t bytesPerCell(int bands);

 private:
  struct Key {
    std::int64_t i, j, k;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    std::size_t operator()(const Key& key) const;
  };
  struct Slot {
    Key key;
    Eigen::Vector3d sum_W;
    std::uint32_t count = 0;
    std::uint32_t generation = 0;  // bumped when freed: stale queue entries are skipped
  };
  struct Due {
    std::int64_t release, order;
    std::uint32_t slot, generation;
    bool operator>(const Due& other) const {
      return release != other.release ? release > other.release : order > other.order;
    }
  };
  static constexpr std::uint32_t kChunk = 4096;  // slots per allocation

  float* sums(std::uint32_t slot) { return &chunks_[slot / kChunk][std::size_t(slot % kChunk) * bands_]; }
  std::uint32_t allocate();
  // Emits the top of the queue if it is current; returns whether it was.
  bool emitTop();

  const CellReleaseMap& releases_;
  int bands_;
  std::int64_t max_pending_cells_;
  CellSink sink_;
  std::unordered_map<Key, std::uint32_t, KeyHash> cells_;
  std::vector<Slot> slots_;
  std::vector<std::unique_ptr<float[]>> chunks_;
  std::vector<std::uint32_t> free_;
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> due_;
  std::vector<float> mean_;
  std::int64_t order_ = 0, added_ = 0, emitted_ = 0, early_ = 0, peak_pending_ = 0;
};

}  // namespace hsmap
