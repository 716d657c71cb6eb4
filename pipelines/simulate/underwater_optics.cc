#include "pipelines/simulate/underwater_optics.h"

#include <algorithm>
#include <cmath>

namespace hsmap {
namespace {
double gaussian(double x, double centre, double width) {
  const double z = (x - centre) / width;
  return std::exp(-0.5 * z * z);
}
}  // namespace

double waterAttenuationPerM(double wavelength_nm, double turbidity) {
  // Clear water: about 0.02 /m in the blue-green, 0.3 /m at 650 nm, 2.5 /m at
  // 750 nm (the shape of pure-water absorption, smoothed).
  const double water = 0.015 + 0.035 * std::exp((wavelength_nm - 560.0) / 55.0);
  // Coloured dissolved organic matter: exponential decay from the blue.
  const double dissolved = 0.04 * std::exp(-0.014 * (wavelength_nm - 440.0));
  // Particles: scattering out of the beam, slowly decreasing with wavelength.
  const double particles = 0.08 * (550.0 / wavelength_nm);
  return water + turbidity * (dissolved + particles);
}

double waterScatteringPerM(double wavelength_nm, double turbidity) {
  // The particle term of waterAttenuationPerM.
  return turbidity * (0.08 * (550.0 / wavelength_nm));
}

double lampSpectrum(double wavelength_nm) {
  const double blue_emitter = 0.9 * gaussian(wavelength_nm, 452.0, 11.0);
  const double phosphor = 0.75 * gaussian(wavelength_nm, 575.0, 55.0);
  // A weak broad tail so that the red edge and near infrared are lit.
  const double tail = 0.25 / (1.0 + std::exp(-(wavelength_nm - 640.0) / 30.0));
  return 0.03 + blue_emitter + phosphor + tail;
}

double rgbResponse(int channel, double wavelength_nm) {
  switch (channel) {
    case 0:
      return gaussian(wavelength_nm, 605.0, 30.0) + 0.15 * gaussian(wavelength_nm, 450.0, 20.0);
    case 1:
      return gaussian(wavelength_nm, 535.0, 35.0);
    default:
      return gaussian(wavelength_nm, 460.0, 28.0);
  }
}

LampRig::LampRig(const SimulatedOpticsConfig& optics, const RigidTransformConfig& T_B_C)
    : power_(optics.lamp_power), beam_exponent_(optics.lamp_beam_exponent) {
  const Eigen::Vector3d camera_B = T_B_C.translation_m;
  camera_B_ = camera_B;
  const double half = optics.lamp_separation_m / 2.0;
  p_B_[0] = camera_B + Eigen::Vector3d(optics.lamp_forward_m, -half, 0.0);
  p_B_[1] = camera_B + Eigen::Vector3d(optics.lamp_forward_m, half, 0.0);
}

LightsConfig LampRig::lightsInCamera(const RigidTransformConfig& T_B_C) const {
  // p_C = R_B_C^T (p_B - t_B_C); the axis turns with R_B_C^T.
  const Eigen::Matrix3d R_C_B = T_B_C.rotation.toRotationMatrix().transpose();
  LightsConfig lights;
  lights.response = "uhi/lamp_response.csv";
  for (int l = 0; l < LampLighting::kMaxLamps; ++l) {
    LampConfig lamp;
    lamp.p_C = R_C_B * (p_B_[l] - T_B_C.translation_m);
    lamp.axis_C = (R_C_B * axis_B_).normalized();
    lights.lamps.push_back(lamp);
  }
  return lights;
}

LampRig::Posed LampRig::posed(const SE3d& T_W_B) const {
  Posed lamps;
  for (int l = 0; l < LampLighting::kMaxLamps; ++l) lamps.lamp_W[l] = T_W_B * p_B_[l];
  lamps.axis_W = T_W_B.q * axis_B_;
  return lamps;
}

BackscatterLamps LampRig::backscatterLamps(const SE3d& T_B_X) const {
  const SE3d T_X_B = T_B_X.inverse();
  BackscatterLamps lamps;
  lamps.power = power_;
  lamps.beam_exponent = beam_exponent_;
  for (const Eigen::Vector3d& p_B : p_B_) {
    lamps.p_X.push_back(T_X_B * p_B);
    lamps.axis_X.push_back((T_X_B.q * axis_B_).normalized());
  }
  return lamps;
}

LampLighting LampRig::lightUnshadowed(const Posed& lamps, const Eigen::Vector3d& p_W,
                                      const Eigen::Vector3d& n_W,
                                      std::array<Ray, LampLighting::kMaxLamps>* shadow_rays) const {
  LampLighting lighting;
  lighting.count = LampLighting::kMaxLamps;
  const Eigen::Vector3d& axis_W = lamps.axis_W;
  for (int l = 0; l < LampLighting::kMaxLamps; ++l) {
    const Eigen::Vector3d to_lamp = lamps.lamp_W[l] - p_W;
    const double r = to_lamp.norm();
    lighting.path_length[l] = r;
    lighting.weight[l] = 0.0;
    if (r < 5e-3) continue;
    const Eigen::Vector3d to_lamp_unit = to_lamp / r;
    const double cos_incidence = n_W.dot(to_lamp_unit);
    const double cos_beam = -axis_W.dot(to_lamp_unit);
    if (cos_incidence <= 0.0 || cos_beam <= 0.0) continue;
    // The default beam (n = 2) without pow(): this runs for every ray.
    const double beam =
        beam_exponent_ == 2.0 ? cos_beam * cos_beam : std::pow(cos_beam, beam_exponent_);
    lighting.weight[l] = power_ * beam * cos_incidence / (r * r);
    if (shadow_rays != nullptr) (*shadow_rays)[l] = Ray{p_W, to_lamp_unit, 2e-3, r - 2e-3};
  }
  return lighting;
}

LampLighting LampRig::light(const SE3d& T_W_B, const Eigen::Vector3d& p_W,
                            const Eigen::Vector3d& n_W, const MeshRayCaster* shadow_caster) const {
  return light(posed(T_W_B), p_W, n_W, shadow_caster);
}

LampLighting LampRig::light(const Posed& lamps, const Eigen::Vector3d& p_W,
                            const Eigen::Vector3d& n_W, const MeshRayCaster* shadow_caster) const {
  std::array<Ray, LampLighting::kMaxLamps> shadow_rays;
  LampLighting lighting = lightUnshadowed(lamps, p_W, n_W, &shadow_rays);
  if (shadow_caster == nullptr) return lighting;
  for (int l = 0; l < lighting.count; ++l) {
    if (lighting.weight[l] > 0.0 && shadow_caster->occluded(shadow_rays[l])) lighting.weight[l] = 0.0;
  }
  return lighting;
}

LampLighting LampRig::nominalLighting(double altitude_m) const {
  const Eigen::Vector3d surface_B = camera_B_ + Eigen::Vector3d(0.0, 0.0, altitude_m);
  return light(SE3d(), surface_B, Eigen::Vector3d(0.0, 0.0, -1.0), nullptr);
}

}  // namespace hsmap
