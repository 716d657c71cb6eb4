#include "pipelines/surface/voxel_point_fusion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hsmap {
namespace {

constexpr std::int64_t kAxisOffset = std::int64_t(1) << 20;
constexpr std::uint64_t kAxisMask = (std::uint64_t(1) << 21) - 1;

}  // namespace

VoxelPointFusion::VoxelPointFusion(double voxel_size_m) : voxel_size_(voxel_size_m) {
  if (!(voxel_size_m > 0.0) || !std::isfinite(voxel_size_m)) {
    throw std::invalid_argument("the fusion voxel size must be > 0");
  }
}

std::uint64_t VoxelPointFusion::keyOf(const Eigen::Vector3d& p_W) const {
  std::uint64_t key = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const std::int64_t index = std::int64_t(std::floor(p_W[axis] / voxel_size_)) + kAxisOffset;
    key = (key << 21) | (std::uint64_t(std::clamp<std::int64_t>(index, 0, kAxisMask)) & kAxisMask);
  }
  return key;
}

void VoxelPointFusion::addView(Voxel& voxel, int keyframe) const {
  for (int i = 0; i < voxel.view_count; ++i) {
    if (voxel.views[std::size_t(i)] == keyframe) return;
  }
  if (voxel.view_count < kMaxViews) voxel.views[voxel.view_count++] = keyframe;
}

void VoxelPointFusion::add(const Eigen::Vector3d& p_W, int reference, int partner) {
  Voxel& voxel = voxels_[keyOf(p_W)];
  voxel.sum += p_W;
  ++voxel.count;
  ++points_added_;
  if (voxel.last_reference != reference) {
    voxel.last_reference = reference;
    if (voxel.support < 255) ++voxel.support;
  }
  addView(voxel, reference);
  addView(voxel, partner);
}

FusedPoints VoxelPointFusion::extract(int min_support) const {
  std::vector<std::uint64_t> keys;
  for (const auto& [key, voxel] : voxels_) {
    if (voxel.support >= min_support) keys.push_back(key);
  }
  std::sort(keys.begin(), keys.end());
  FusedPoints fused;
  fused.p_W.reserve(keys.size());
  fused.views.reserve(keys.size());
  fused.support.reserve(keys.size());
  for (std::uint64_t key : keys) {
    const Voxel& voxel = voxels_.at(key);
    fused.p_W.push_back(voxel.sum / double(voxel.count));
    fused.views.emplace_back(voxel.views.begin(), voxel.views.begin() + voxel.view_count);
    fused.support.push_back(voxel.support);
  }
  fused.keys = std::move(keys);
  return fused;
}

}  // namespace hsmap
