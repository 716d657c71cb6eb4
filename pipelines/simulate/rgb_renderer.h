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
// misses sees black water. With optics.backscatter, each ray also gets the
// light the water scatters into it up to its hit (or the maximum range)
// (water_backscatter.h), from a table over a grid of rays every
// kBackscatterGridPx pixels, interpolated bilinearly in the image. With
// optics.marine_snow, each frame draws its own particles (rgb_marine_snow.h)
// at the pose of its middle sub-frame and adds them to every sub-frame.
//
// Exposure: a frame is the average of its sub-frames (rgb_motion_blur.h; one
// for an instantaneous exposure), each rendered from its own camera and body
// pose. The linear value is multiplied by the vignetting (rgb_vignetting.h),
// scaled by a fixed exposure (a flat surface of
// `exposure_reflectance` on the axis at the nominal altitude reaches 250 DN)
// times the frame's gain (automatic gain; 1 for the fixed exposure), given
// shot and read noise, rounded and clipped to 8 bits. A gain G amplifies the
// sensor's noise with the signal: read noise sigma_r becomes G sigma_r and the
// shot-noise variance G DN / electrons_per_dn (fewer electrons per DN). The
// image is linear (no gamma) and in OpenCV's BGR order.
//
// Rows are rendered in parallel (TBB); each row's noise has its own seed, so
// the bytes do not depend on scheduling. With one sub-frame and a gain of 1
// the frame is bit for bit the instantaneous render.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "core/geometry/se3.h"
#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/rgb_radiance_table.h"
#include "pipelines/simulate/simulation_config.h"
#include "pipelines/simulate/water_backscatter.h"

namespace hsmap {

class RgbRenderer {
 public:
  RgbRenderer(const RenderContext& context, const SimulatedRgbConfig& config, std::uint64_t seed);

  // Where the camera is at one instant of the exposure: T_W_C sees, the body
  // pose T_W_B places the lamps.
  struct Pose {
    SE3d T_W_B;
    SE3d T_W_C;
  };

  // Frame `frame_index` seen from T_W_C (the body pose T_W_B lights the scene).
  cv::Mat render(const SE3d& T_W_B, const SE3d& T_W_C, std::int64_t frame_index) const;
  // Frame `frame_index` exposed over `subframes` (equal weights, at least
  // one) with the linear gain `gain` (> 0) on top of the fixed exposure.
  cv::Mat render(std::span<const Pose> subframes, double gain, std::int64_t frame_index) const;

 private:
  RenderContext context_;
  SimulatedRgbConfig config_;
  std::uint64_t seed_;
  RgbRadianceTable table_;
  double gain_ = 1.0;
  // Linear RGB (before exposure) of the hit point p_W lit as `lighting`.
  Eigen::Vector3f shade(const Eigen::Vector3d& p_W, const RayHit& hit,
                        const LampLighting& lighting) const;
  // Casts and shades `count` rays of `rays_C` from T_W_C into `out`; `uv`
  // holds the rays' image points (for the backscatter; null when it is off).
  void shadeRays(const SE3d& T_W_B, const SE3d& T_W_C, const Eigen::Vector3d* rays_C,
                 const Eigen::Vector2f* uv, int count, Eigen::Vector3f* out) const;
  // Adds the marine snow `particles` seen from `pose` to the linear image.
  void drawMarineSnow(const std::vector<SnowParticle>& particles, const Pose& pose,
                      std::vector<Eigen::Vector3f>& linear) const;
  // Adds the backscatter of the ray through image point uv whose water path
  // is range_m long.
  void addBackscatter(const Eigen::Vector2f& uv, double range_m, Eigen::Vector3f& linear) const;
  // The anti-aliased linear image (row-major, before exposure) seen from
  // `pose`, added to `sum` when `accumulate`, else written to it.
  void renderLinear(const Pose& pose, std::vector<Eigen::Vector3f>& sum, bool accumulate) const;

  // Unit ray directions in C, row-major: samples_per_pixel per pixel (1, 4),
  // or the pixel centres (2) followed by corner_rays_C_.
  std::vector<Eigen::Vector3d> rays_C_;
  std::vector<Eigen::Vector3d> corner_rays_C_;  // (height + 1) x (width + 1), quincunx only
  std::vector<float> vignetting_;                // per pixel, row-major; empty: none
  // Backscatter (null when off): the table's rays on a grid over the image,
  // nodes at u = -0.5 + i * width / (grid_u_ - 1) (and v alike), row-major;
  // the image point of every ray of rays_C_ and corner_rays_C_.
  static constexpr int kBackscatterGridPx = 16;
  std::unique_ptr<WaterBackscatterTable> backscatter_;
  int grid_u_ = 0, grid_v_ = 0;
  std::vector<Eigen::Vector2f> uv_;
  std::vector<Eigen::Vector2f> corner_uv_;
};

}  // namespace hsmap
