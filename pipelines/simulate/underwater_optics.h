#pragma once
// The light path of the simulator: vehicle lamps -> water -> seabed -> water ->
// camera, for a Lambertian seabed.
//
// For a surface point p with reflectance rho(lambda) lit by lamps l, the
// radiance reaching a camera at distance r_cam is
//   L(lambda) = rho(lambda) / pi * sum_l g_l * I(lambda) * exp(-c(lambda) (r_l + r_cam))
// with g_l = power * cos^n(angle off the lamp axis) * cos(incidence) / r_l^2
// (zero when the point faces away from the lamp or, with shadows on, when the
// scene blocks the lamp), I the lamp spectrum and c the water's beam
// attenuation (Beer-Lambert along both paths). Light that the water scatters
// into the camera on the way (backscatter) is added by water_backscatter.h
// when optics.backscatter is on; forward scattering is not modelled.
//
// The spectra are smooth analytic curves over 350-1000 nm:
//   waterAttenuationPerM: clear-water absorption rising steeply into the red
//     and near infrared, plus coloured dissolved matter (high in the blue) and
//     particles (slowly decreasing), the last two scaled by `turbidity`;
//   waterScatteringPerM: the particles' part of c, b(lambda) <= c(lambda), the
//     light they scatter rather than absorb (backscatter's source; pure
//     water's molecular scattering, below 0.004 /m, is neglected);
//   lampSpectrum: a white LED (blue emitter near 450 nm and a broad phosphor
//     band near 570 nm) extended by a halogen-like tail into the infrared, so
//     that every UHI band receives light;
//   rgbResponse: Gaussian-like red, green and blue sensitivities (channel 0 =
//     red, 1 = green, 2 = blue).
#include <array>

#include <Eigen/Core>

#include "core/geometry/se3.h"
#include "core/raycast/mesh_ray_caster.h"
#include "core/survey/lights_config.h"
#include "core/survey/survey_config.h"
#include "pipelines/simulate/simulation_config.h"

namespace hsmap {

double waterAttenuationPerM(double wavelength_nm, double turbidity);
double waterScatteringPerM(double wavelength_nm, double turbidity);
double lampSpectrum(double wavelength_nm);
double rgbResponse(int channel, double wavelength_nm);

// The lamps' geometric weights g_l and path lengths r_l for one surface point.
struct LampLighting {
  static constexpr int kMaxLamps = 2;
  int count = 0;
  std::array<double, kMaxLamps> weight{};       // g_l
  std::array<double, kMaxLamps> path_length{};  // r_l, metres
};

// Two lamps, port and starboard of the RGB camera, pointing down (+z_B).
class LampRig {
 public:
  // The lamps in W for one body pose: computed once per frame or line
  // instead of once per ray.
  struct Posed {
    std::array<Eigen::Vector3d, LampLighting::kMaxLamps> lamp_W;
    Eigen::Vector3d axis_W;
  };

  LampRig(const SimulatedOpticsConfig& optics, const RigidTransformConfig& T_B_C);
  const std::array<Eigen::Vector3d, LampLighting::kMaxLamps>& lampPositions_B() const {
    return p_B_;
  }
  const Eigen::Vector3d& axis_B() const { return axis_B_; }
  double power() const { return power_; }
  double beamExponent() const { return beam_exponent_; }
  // The lamps as survey.yaml's `lights.lamps` states them (the data
  // contract): centres and beam axes in the RGB camera frame C.
  LightsConfig lightsInCamera(const RigidTransformConfig& T_B_C) const;
  // Lighting of the surface point p_W with unit normal n_W (facing the viewer)
  // when the body is at T_W_B. With `shadow_caster`, lamps hidden by the scene
  // contribute nothing.
  LampLighting light(const SE3d& T_W_B, const Eigen::Vector3d& p_W, const Eigen::Vector3d& n_W,
                     const MeshRayCaster* shadow_caster) const;
  // The same with the lamps already posed (once per frame or line).
  LampLighting light(const Posed& lamps, const Eigen::Vector3d& p_W, const Eigen::Vector3d& n_W,
                     const MeshRayCaster* shadow_caster) const;
  // light() without shadows, plus the shadow ray of every lamp that lights
  // the point (weight > 0): from p_W towards the lamp, skipping 2 mm at both
  // ends so it finds neither the surface it starts on nor the lamp. For
  // renderers that test many shadow rays in one batch.
  LampLighting lightUnshadowed(const Posed& lamps, const Eigen::Vector3d& p_W,
                               const Eigen::Vector3d& n_W,
                               std::array<Ray, LampLighting::kMaxLamps>* shadow_rays) const;
  Posed posed(const SE3d& T_W_B) const;
  // The lamps in the frame X of a camera fixed to the body at T_B_X, for the
  // backscatter integral (water_backscatter.h).
  BackscatterLamps backscatterLamps(const SE3d& T_B_X) const;
  // Lighting of a flat seabed `altitude_m` straight below the RGB camera with
  // the body level: the reference geometry of the cameras' fixed exposure.
  LampLighting nominalLighting(double altitude_m) const;

 private:
  std::array<Eigen::Vector3d, LampLighting::kMaxLamps> p_B_;
  Eigen::Vector3d camera_B_;
  Eigen::Vector3d axis_B_{0.0, 0.0, 1.0};
  double power_;
  double beam_exponent_;
};

// Attenuation-weighted radiance per unit reflectance at one wavelength:
// sum_l g_l I exp(-c (r_l + r_cam)) / pi.
inline double lampRadianceFactor(const LampLighting& lighting, double lamp_intensity,
                                 double attenuation_per_m, double camera_distance_m);

}  // namespace hsmap

#include <cmath>
#include <numbers>

namespace hsmap {
inline double lampRadianceFactor(const LampLighting& lighting, double lamp_intensity,
                                 double attenuation_per_m, double camera_distance_m) {
  double sum = 0.0;
  for (int l = 0; l < lighting.count; ++l) {
    sum += lighting.weight[l] *
           std::exp(-attenuation_per_m * (lighting.path_length[l] + camera_distance_m));
  }
  return sum * lamp_intensity / std::numbers::pi;
}
}  // namespace hsmap
