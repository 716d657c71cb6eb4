#pragma once
// VoxelPointFusion: the dense points of many stereo pairs merged into one
// point per voxel of a fixed grid, keeping the keyframes that saw it.
//
// Every point of a pair (reference keyframe r, partner o) falls in a voxel;
// the voxel keeps the sum of its points, how many came in, the distinct
// reference keyframes whose depth maps put a point there (its support) and
// the keyframes that saw it (r and o of each pair, up to kMaxViews). A
// voxel supported by one depth map only is a point no other pair agrees
// with (a mismatch, a reflection) and is dropped; the points of a voxel
// supported by several are averaged, which also averages their noise.
//
// The grid is global (voxel (i, j, k) covers [i, i+1) * size, ... from the
// origin of W), so two blocks of the survey fused from the same depth maps
// give the same point, with the same key, where they overlap; the key is
// how the blocks' meshes are stitched (dense_surface.h).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace hsmap {

struct FusedPoints {
  std::vector<Eigen::Vector3d> p_W;
  std::vector<std::vector<int>> views;  // keyframe ids
  std::vector<std::uint64_t> keys;      // voxel key of each point
  std::vector<int> support;             // distinct depth maps that agree
};

class VoxelPointFusion {
 public:
  static constexpr int kMaxViews = 8;

  // Throws std::invalid_argument unless voxel_size_m > 0.
  explicit VoxelPointFusion(double voxel_size_m);

  // One point of the depth map of `reference` paired with `partner`.
  void add(const Eigen::Vector3d& p_W, int reference, int partner);

  // The voxels with at least `min_support` depth maps, in key order (so the
  // result does not depend on the order points came in).
  FusedPoints extract(int min_support) const;

  std::size_t voxelCount() const { return voxels_.size(); }
  std::uint64_t pointsAdded() const { return points_added_; }
  double voxelSize() const { return voxel_size_; }
  // The key of the voxel holding p_W (21 bits per axis, +-2^20 voxels).
  std::uint64_t keyOf(const Eigen::Vector3d& p_W) const;

 private:
  struct Voxel {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    std::uint8_t view_count = 0;
    std::uint8_t support = 0;
    int last_reference = -1;  // the depth maps of one reference arrive together
    std::array<int, kMaxViews> views{};
  };
  void addView(Voxel& voxel, int keyframe) const;

  double voxel_size_;
  std::unordered_map<std::uint64_t, Voxel> voxels_;
  std::uint64_t points_added_ = 0;
};

}  // namespace hsmap
