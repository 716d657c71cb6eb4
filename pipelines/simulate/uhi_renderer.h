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
//
// With optics.backscatter, each pixel also gets the light the water scatters
// into it (water_backscatter.h), before noise:
//   DN_bs,b = gain * I_b * b_b * integral(...) = pi K_b / P * L_bs,b / I_b,
// i.e. pi K(lambda) times the integral of sum_l B/r_l^2 exp(-c (r_l + s))
// beta(psi_l) ds with beta = b p, K the contract's lamp response
// (lampResponseDn) and P the lamp power (K holds one P). It is looked up at the mean
// range of the pixel's rays that hit (the maximum range for those that miss)
// in a table over the rays of every kBackscatterGridSamples-th sample along
// the line (the line's central ray across it), interpolated linearly.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/se3.h"
#include "pipelines/simulate/render_context.h"
#include "pipelines/simulate/simulation_config.h"
#include "pipelines/simulate/water_backscatter.h"

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

  // The contract's constant backscatter(lambda) as truth/calibration.yaml's
  // backscatter_dn states it: per band, the backscatter DN (no noise) of the
  // ray through the principal point (cx), with the body level over a flat
  // seabed at the nominal altitude below the RGB camera, up to the seabed.
  // Empty when optics.backscatter is off.
  std::vector<double> nominalBackscatterDn() const;
  // The backscatter DN of every band for the ray of line position u (pixels)
  // over a water path of range_m (no noise; zeros when off).
  Eigen::VectorXf backscatterDn(double u, double range_m) const;

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
  // Backscatter (null when off): rays at u = -0.5 + i * samples / (grid_ - 1).
  static constexpr int kBackscatterGridSamples = 8;
  std::unique_ptr<WaterBackscatterTable> backscatter_;
  int grid_ = 0;
  // Adds weight * the backscatter (before the DN scale) of line position u
  // over range_m to out (bands values).
  void addBackscatter(double u, double range_m, float weight, float* out) const;
};

// Band centres: `bands` values spread evenly over [min, max] nm.
std::vector<double> uhiBandCentres(const SimulatedUhiConfig& config);

}  // namespace hsmap
