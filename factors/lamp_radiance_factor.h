#pragma once
// LampRadianceFactor: one UHI pixel's digital number in one band, as the
// contract's radiometric model predicts it (shared/DATASET.md, "Radiometry";
// docs/RADIOMETRY.md):
//
//   DN(λ) = K(λ) · ρ(λ) · Σ_l [ B(θ_l) · cos(i_l) / r_l² · exp(−c(λ) · (r_l + r_u)) ] + o(λ)
//
// with r_l the lamp-to-point distance, i_l the incidence angle of lamp l's
// light on the surface, θ_l the angle off lamp l's axis, r_u the
// point-to-UHI distance, K(λ) the lamp response (uhi/lamp_response.csv),
// c(λ) the water's attenuation and o(λ) the backscatter.
//
// The beam B(θ) is shared by the lamps (one make) and modelled as the
// exponential of an even polynomial in θ with B(0) = 1:
//
//   B(θ) = exp(m_1 θ² + m_2 θ⁴)
//
// Why this form: it is smooth and symmetric about the axis (a lamp's beam
// is), positive for any coefficients (no bound needed in the solve), exactly
// 1 on the axis (K is measured there), and its logarithm is linear in the
// coefficients, so the solve is well conditioned. It contains the cos^n(θ)
// beams of LED reflectors to fourth order (ln cos θ = −θ²/2 − θ⁴/12 − ...),
// and a Gaussian beam exactly (m_2 = 0).
//
// The reflectance is ρ = exp(r) so that it stays positive; r is the
// variable (one per seabed point and band).
//
//   variables  c = C(band) (1/m), o = O(band) (DN), r = R(point*bands+band)
//              (log reflectance), m = M(0) ([m_1, m_2], 1/rad², 1/rad⁴)
//   residual   predicted DN − measured DN                     (1, DN)
// The noise model (DN) and robust loss are the caller's: the spread of one
// seabed point's DN is the sensor's noise plus the reflectance's own
// variation within the point's cell.
//
// Lamps that do not light the point (behind it, in its shadow) are left out
// of `lamps` by the caller; a factor needs at least one lamp.

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/key.h"
#include "core/graph/noise_model.h"
#include "factors/ceres_factor.h"

namespace hsmap {

// One lamp's light path to the seabed point.
struct LampPath {
  double range_m = 1.0;        // r_l, lamp centre to the point, metres (> 0)
  double cos_incidence = 1.0;  // cos(i_l), in (0, 1]
  double off_axis_rad = 0.0;   // θ_l, angle between the lamp's axis and the ray to the point
};

inline constexpr int kLampBeamCoefficients = 2;

// B(θ) = exp(m_1 θ² + m_2 θ⁴).
template <class T>
T lampBeam(double off_axis_rad, const T* beam) {
  using std::exp;
  const double t2 = off_axis_rad * off_axis_rad;
  return exp(beam[0] * t2 + beam[1] * (t2 * t2));
}

// Σ_l B(θ_l) cos(i_l) / r_l² exp(−c (r_l + r_u)): the illumination the
// lamps give the point, as the UHI sees it through the water (1/m²).
template <class T>
T lampIllumination(const std::vector<LampPath>& lamps, double uhi_range_m, const T& attenuation_per_m,
                   const T* beam) {
  using std::exp;
  T sum(0.0);
  for (const LampPath& lamp : lamps) {
    sum += lampBeam(lamp.off_axis_rad, beam) * (lamp.cos_incidence / (lamp.range_m * lamp.range_m)) *
           exp(-attenuation_per_m * (lamp.range_m + uhi_range_m));
  }
  return sum;
}

// Ceres functor: (c [1], o [1], r [1], m [2]) -> residual [1].
struct LampRadianceResidual {
  double dn;                    // measured DN
  double response_dn;           // K(λ)
  double uhi_range_m;           // r_u
  std::vector<LampPath> lamps;  // the lamps that light the point

  template <class T>
  bool operator()(const T* attenuation, const T* backscatter, const T* log_reflectance, const T* beam,
                  T* residual) const {
    using std::exp;
    residual[0] = response_dn * exp(log_reflectance[0]) *
                      lampIllumination(lamps, uhi_range_m, attenuation[0], beam) +
                  backscatter[0] - dn;
    return true;
  }
};

class LampRadianceFactor : public CeresFactor {
 public:
  static constexpr int kResidualDimension = 1;

  // Throws std::invalid_argument for a noise model that is not
  // 1-dimensional, a non-finite DN, a response <= 0, a range <= 0, no lamp,
  // or a lamp path outside the ranges above.
  LampRadianceFactor(Key attenuation, Key backscatter, Key log_reflectance, Key beam,
                     LampRadianceResidual measurement, NoiseModel noise, RobustLoss loss);

  std::string name() const override { return "LampRadianceFactor"; }
  std::unique_ptr<ceres::CostFunction> createCostFunction() const override;

  const LampRadianceResidual& measurement() const { return measurement_; }

 private:
  LampRadianceResidual measurement_;
};

}  // namespace hsmap
