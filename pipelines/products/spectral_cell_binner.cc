#include "pipelines/products/spectral_cell_binner.h"

#include <stdexcept>
#include <string>
#include <utility>

namespace hsmap {

std::size_t SpectralCellBinner::KeyHash::operator()(const Key& key) const {
  std::uint64_t h = std::uint64_t(key.i) * 0x9E3779B97F4A7C15ull;
  h ^= std::uint64_t(key.j) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= std::uint64_t(key.k) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  return std::size_t(h ^ (h >> 29));
}

std::int64_t SpectralCellBinner::bytesPerCell(int bands) {
  // sums + slot + hash node (key, value, next, bucket) + queue entry
  return std::int64_t(bands) * 4 + std::int64_t(sizeof(Slot)) + 56 + std::int64_t(sizeof(Due));
}

SpectralCellBinner::SpectralCellBinner(const CellReleaseMap& releases, int bands, std::int64_t max_pending_bytes,
                                       CellSink sink)
    : releases_(releases), bands_(bands), sink_(std::move(sink)), mean_(std::size_t(std::max(bands, 1))) {
  if (bands < 1 || max_pending_bytes < bytesPerCell(std::max(bands, 1))) {
    throw std::invalid_argument("SpectralCellBinner: " + std::to_string(bands) + " bands, a bound of " +
                                std::to_string(max_pending_bytes) + " bytes");
  }
  max_pending_cells_ = max_pending_bytes / bytesPerCell(bands);
}

std::uint32_t SpectralCellBinner::allocate() {
  if (!free_.empty()) {
    const std::uint32_t slot = free_.back();
    free_.pop_back();
    return slot;
  }
  const auto slot = std::uint32_t(slots_.size());
  if (slot % kChunk == 0) chunks_.emplace_back(new float[std::size_t(kChunk) * std::size_t(bands_)]);
  slots_.emplace_back();
  return slot;
}

void SpectralCellBinner::add(const Eigen::Vector3d& p_W, const float* spectrum) {
  const double c = releases_.cellSize();
  const Key key{latticeIndex(p_W.x(), c), latticeIndex(p_W.y(), c), latticeIndex(p_W.z(), c)};
  ++added_;
  auto [it, created] = cells_.try_emplace(key, 0u);
  if (!created) {
    Slot& slot = slots_[it->second];
    slot.sum_W += p_W;
    ++slot.count;
    float* sum = sums(it->second);
    for (int b = 0; b < bands_; ++b) sum[b] += spectrum[b];
    return;
  }
  const std::uint32_t index = allocate();
  it->second = index;
  Slot& slot = slots_[index];
  slot.key = key;
  slot.sum_W = p_W;
  slot.count = 1;
  float* sum = sums(index);
  for (int b = 0; b < bands_; ++b) sum[b] = 0.0f + spectrum[b];  // -0 becomes +0, as a cleared sum
  due_.push({releases_.release(key.i, key.j), order_++, index, slot.generation});
  peak_pending_ = std::max(peak_pending_, pendingCells());
  if (pendingCells() > max_pending_cells_) {
    const std::int64_t target = max_pending_cells_ * 3 / 4;
    while (pendingCells() > target && !due_.empty()) early_ += emitTop() ? 1 : 0;
  }
}

bool SpectralCellBinner::emitTop() {
  const Due due = due_.top();
  due_.pop();
  Slot& slot = slots_[due.slot];
  if (slot.generation != due.generation) return false;
  const float* sum = sums(due.slot);
  const float scale = 1.0f / float(slot.count);
  for (int b = 0; b < bands_; ++b) mean_[std::size_t(b)] = sum[b] * scale;
  CellPoint point;
  point.p_W = slot.sum_W / double(slot.count);
  point.hits = slot.count;
  point.spectrum = mean_.data();
  sink_(point);
  ++emitted_;
  cells_.erase(slot.key);
  ++slot.generation;
  free_.push_back(due.slot);
  return true;
}

void SpectralCellBinner::releaseThrough(std::int64_t sequence) {
  while (!due_.empty() && due_.top().release <= sequence) emitTop();
}

void SpectralCellBinner::releaseAll() {
  while (!due_.empty()) emitTop();
}

}  // namespace hsmap
