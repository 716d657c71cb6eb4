#pragma once
// The water and the lamps self-calibrated (docs/RADIOMETRY.md): from the
// radiometric observations (radiometric_observations.h), one robust sparse
// least-squares problem (Ceres, through the engine's GraphProblem) estimates
//
//   c(λ)      the water's attenuation per UHI band          C(band), 1/m
//   o(λ)      the backscatter per band (when asked)         O(band), DN
//   m_1, m_2  the lamps' shared beam B(θ) = exp(m_1 θ² + m_2 θ⁴)   M(0)
//   ρ_p(λ)    every seabed point's reflectance (nuisance)   R(p·bands + band), log
//
// with one LampRadianceFactor per observation and band (the contract's model,
// factors/lamp_radiance_factor.h) and K(λ) given (uhi/lamp_response.csv).
//
// Noise. The residual of a factor is in DN; its sigma is
//   σ = relative_noise · (the observation's DN) + noise_floor_dn
// (the reflectance's variation within a point's cell and the shot noise grow
// with the signal, which varies several-fold over one point's geometries: a
// sigma from the point's median would under-weight its near views and bias
// the beam; the floor is the read noise), under a Cauchy loss of
// `loss_scale` sigmas (a cell straddling two materials, a pixel on a mis-meshed
// stone).
//
// Priors (GaussianPriorFactor), so that what the survey does not determine
// falls back on physics instead of wandering (and is named in a warning):
//   c(λ) ~ N(a_w(λ) + attenuation_prior_offset_per_m, attenuation_prior_sigma_per_m²)
//     with a_w pure water's absorption (pure_water_absorption.h): natural
//     water attenuates more than pure water, by ~0.05–1 /m;
//   m ~ N(0, beam_prior_sigma²) per coefficient (a flat beam, loosely).
// Where the data determine a parameter its sigma is far below the prior's,
// which then moves it by a negligible fraction of that sigma.
//
// Bounds: c(λ) in [0, 50] /m (water never amplifies light) and every ρ in
// [1e-4, 10] (a point whose every view the loss rejects must not run off to
// an overflowing prediction, which would also swamp the covariance).
//
// Start. c = initial_attenuation_per_m in every band (the prior's mean when
// not given), o = 0, a flat beam
// (m = 0), and each ρ_p(λ) the median over its observations of DN / (K · the
// lamps' illumination at that start): the reflectances are then consistent
// with the start and the solver moves the shared parameters.
//
//   c(λ) smooth in λ: SecondDifferencePriorFactor on every three neighbouring
//     bands (attenuation_smoothness_per_m), so that a band the data leave
//     undetermined (a dark band in the near infrared) follows its neighbours.
//
// 1-sigma. The marginal covariance of C, O and M under the Gauss-Newton
// approximation, the reflectances eliminated exactly by their Schur
// complement (one scalar per point and band: a (2B + 2)² system; Ceres' sparse
// QR covariance, solvers/marginal_covariance.h, misjudged this problem's rank
// on the tiny survey, where the reduced system is well conditioned), scaled
// by the fit's own residual variance (the robust cost per degree of
// freedom), since the noise model's relative_noise is a guess. When the
// backscatter is not determined (rank deficient, or a 1-sigma above
// max_backscatter_sigma_dn in a band) it is held at zero, the problem solved
// again and a warning says so. A band whose c has a 1-sigma above max_attenuation_sigma_per_m is named
// in a warning (the survey does not determine it: a constant range over
// every point, e.g. a constant altitude over a flat seabed), and so is a beam
// whose coefficients are not determined to max_beam_sigma.

#include <optional>
#include <string>
#include <vector>

#include "core/survey/water_estimate.h"
#include "pipelines/radiometry/radiometric_observations.h"
#include "solvers/graph_solver.h"

namespace hsmap {

struct WaterEstimationOptions {
  std::optional<double> initial_attenuation_per_m;  // > 0; default: the prior's mean per band
  double attenuation_prior_offset_per_m = 0.1;      // >= 0
  double attenuation_prior_sigma_per_m = 0.3;       // > 0
  double beam_prior_sigma = 3.0;                    // > 0
  // Smoothness of c(λ): 1-sigma of its second difference over three bands
  // 10 nm apart (scaled by the square of the actual spacing); 0: none.
  double attenuation_smoothness_per_m = 0.03;       // >= 0
  double relative_noise = 0.1;             // > 0
  double noise_floor_dn = 1.0;             // > 0
  double loss_scale = 3.0;                 // Cauchy scale, sigmas, > 0
  bool estimate_backscatter = true;
  // Above these 1-sigma, the warning names the band / the beam.
  double max_attenuation_sigma_per_m = 0.02;
  double max_beam_sigma = 0.5;
  double max_backscatter_sigma_dn = 5.0;  // above, in any band: backscatter held at zero
  int max_iterations = 50;
  int num_threads = 0;  // 0: every core

  // std::invalid_argument naming the field.
  void validate() const;
};

struct WaterEstimationReport {
  WaterEstimate water;
  SolveReport solve;
  bool backscatter_estimated = false;
  bool covariance_computed = false;
  double residual_scale = 1.0;  // sqrt(2 · cost / (residuals − free parameters))
  int observations = 0;
  int points = 0;
  double covariance_seconds = 0.0;

  // For people: the solve, c and its sigma per band, the beam, the warnings.
  std::string summary(const std::vector<double>& wavelengths_nm) const;
};

// Throws std::invalid_argument for bad options, a response with the wrong
// number of bands or one <= 0, or no observation.
// `wavelengths_nm` (one per band) place the prior on c.
WaterEstimationReport estimateWater(const RadiometricObservations& observations,
                                    const std::vector<double>& response_dn,
                                    const std::vector<double>& wavelengths_nm,
                                    const WaterEstimationOptions& options = {});

}  // namespace hsmap
