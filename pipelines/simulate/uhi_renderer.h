#pragma once
// UhiRenderer: one push-broom scan line by ray casting the scene with Embree.
//
// Each pixel integrates over its instantaneous field of view: n x n rays
// spread over one pixel along the line and over `ifov_across_deg` across it
// (one pixel's angle, 1/f rad, when 0), through the true, distorted line
// camera. Each ray is lit by the lamps (underwater_optics.h); the pixel's
// spectrum is
//   L_b = I_b / pi * sum_l exp(-c_b Lbar_l) * (E * w_l)_b,
//   w_l = mean over the rays of g_l * abundances,
// where Lbar_l is the mean path length lamp -> surface -> camera of lamp l over
// the pixel's rays (the rays of one pixel differ in length by millimetres, so
// exp(-c L) varies by less than 1e-3 across them), E the endmember spectra at
// the band centres and I the lamp spectrum. Values are scaled by a fixed
// exposure (a flat surface of `exposure_reflectance` on the axis at the
// nominal altitude reaches 60000 DN in its brightest band), given shot and
// read noise and clipped to [0, 65535]. A ray that misses sees black water.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/se3.h"
#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/simulation_config.h"

namespace hsmap {

struct UhiLineImage {
  Eigen::MatrixXf dn;  // bands x samples, digital numbers (not yet rounded)
  // Surface point hit by each pixel's central ray in W; NaN for a miss.
  std::vector<Eigen::Vector3d> centre_hits_W;
};

class UhiRenderer {
 public:
  UhiRenderer(const RenderContext& context, const SimulatedUhiConfig& config,
              std::vector<double> wavelengths_nm, std::uint64_t seed);

  // Scan line `line_index` exposed from T_W_U (the body pose T_W_B lights the scene).
  void render(const SE3d& T_W_B, const SE3d& T_W_U, std::int64_t line_index,
              UhiLineImage& out) const;

  // The data contract's K(lambda) per band (uhi/lamp_response.csv): the DN
  // one lamp alone gives from a white Lambertian target 1 m away on its axis,
  // facing it, with no water: the lamp's weight there is its power (beam 1,
  // cos 1, 1/r^2 = 1), so K = gain * power * I(lambda) / pi, exactly the
  // factor render() multiplies each lamp's light by (before noise).
  std::vector<double> lampResponseDn() const;

 private:
  RenderContext context_;
  SimulatedUhiConfig config_;
  std::vector<double> wavelengths_nm_;
  std::uint64_t seed_;
  Eigen::ArrayXf attenuation_;  // c_b
  Eigen::ArrayXf lamp_;         // I_b
  Eigen::MatrixXf endmembers_;  // E: bands x endmembers
  double gain_ = 1.0;
  int rays_per_pixel_ = 1;
  std::vector<Eigen::Vector3d> rays_U_;        // rays_per_pixel_ per sample
  std::vector<Eigen::Vector3d> centre_rays_U_;  // one per sample
};

// Band centres: `bands` values spread evenly over [min, max] nm.
std::vector<double> uhiBandCentres(const SimulatedUhiConfig& config);

}  // namespace hsmap
