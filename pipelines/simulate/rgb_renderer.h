#pragma once
// RgbRenderer: one RGB video frame by ray casting the scene with Embree.
//
// Anti-aliasing, by `samples_per_pixel` rays per pixel through the true,
// distorted camera:
//   1  the pixel centre only (no anti-aliasing);
//   2  quincunx: the centre with weight 1/2 and the four pixel corners with
//      1/8 each; a corner is shared by four pixels, so this costs two rays
//      per pixel for a five-tap filter (the default: it halves the cost of 4);
//   4  a rotated 4-point grid inside the pixel, equal weights. A ray that hits the
// seabed is shaded with the lamps, the water and the endmember mixture of the
// material field (underwater_optics.h, rgb_radiance_table.h); a ray that
// misses sees black water. The linear value is scaled by a fixed exposure (a
// flat surface of `exposure_reflectance` on the axis at the nominal altitude
// reaches 250 DN), given shot and read noise, rounded and clipped to 8 bits.
// The image is linear (no gamma) and in OpenCV's BGR order.
//
// Rows are rendered in parallel (TBB); each row's noise has its own seed, so
// the bytes do not depend on scheduling.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/geometry/se3.h"
#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/rgb_radiance_table.h"
#include "pipelines/simulate/simulation_config.h"

namespace hsmap {

class RgbRenderer {
 public:
  RgbRenderer(const RenderContext& context, const SimulatedRgbConfig& config, std::uint64_t seed);

  // Frame `frame_index` seen from T_W_C (the body pose T_W_B lights the scene).
  cv::Mat render(const SE3d& T_W_B, const SE3d& T_W_C, std::int64_t frame_index) const;

 private:
  RenderContext context_;
  SimulatedRgbConfig config_;
  std::uint64_t seed_;
  RgbRadianceTable table_;
  double gain_ = 1.0;
  // Linear RGB (before exposure) of the hit point p_W lit as `lighting`.
  Eigen::Vector3f shade(const Eigen::Vector3d& p_W, const RayHit& hit,
                        const LampLighting& lighting) const;
  // Casts and shades `count` rays of `rays_C` from T_W_C into `out`.
  void shadeRays(const SE3d& T_W_B, const SE3d& T_W_C, const Eigen::Vector3d* rays_C, int count,
                 Eigen::Vector3f* out) const;

  // Unit ray directions in C, row-major: samples_per_pixel per pixel (1, 4),
  // or the pixel centres (2) followed by corner_rays_C_.
  std::vector<Eigen::Vector3d> rays_C_;
  std::vector<Eigen::Vector3d> corner_rays_C_;  // (height + 1) x (width + 1), quincunx only
};

}  // namespace hsmap
