#pragma once
// Backscatter (optics.backscatter): the lamps' light scattered once by the
// water into a camera ray, before the ray reaches the seabed.
//
// Model: single scattering along the ray, as in the Jaffe-McGlamery model of
// underwater imaging (J. S. Jaffe, "Computer modeling and the design of
// optimal underwater imaging systems", IEEE J. Oceanic Eng. 15(2), 1990;
// B. L. McGlamery, SPIE 208, 1980). A camera at the origin looks along the
// unit ray d; the water at x = s d, 0 < s < R (R the range to the seabed, or
// max_range_m for a ray that misses it), is lit by each lamp l at p_l with
// axis a_l, and scatters towards the camera:
//   L_bs(lambda) = I(lambda) b(lambda) integral_{near}^{R} sum_l
//       P B(theta_l) / r_l^2 exp(-c(lambda) r_l) p(psi_l) exp(-c(lambda) s) ds
// with r_l = |x - p_l|, B(theta) = cos^n(theta) the beam (theta off a_l;
// zero behind the lamp), P the lamp power and I its spectrum (the seabed's
// lighting uses the same lamp: underwater_optics.h), c the beam attenuation,
// b <= c the scattering coefficient of the particles (waterScatteringPerM),
// and p the Henyey-Greenstein phase function at the scattering angle psi_l
// between the light's direction (x - p_l) / r_l and the way back, -d:
//   p(psi) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos psi)^(3/2))   [1/sr]
// (L. G. Henyey, J. L. Greenstein, Astrophys. J. 93, 1941); g = 0.924 gives
// a backscattering fraction of 0.017, close to Petzold's average particle
// phase function (0.018; C. D. Mobley, Light and Water, 1994, ch. 3).
// Shadows of the scene in the water (a rock between a lamp and the water in
// front of the camera) are not modelled: the water is lit as if the scene
// were not there.
//
// Quadrature: the midpoint rule over `steps` intervals of [near_m,
// max_range_m], spaced quadratically, s_k = near + (max - near) (k / steps)^2,
// so that they are finest next to the camera where the lamps' light changes
// fastest. For a rig fixed to the vehicle the integral of a ray depends only
// on the ray (in the camera frame) and R: the table keeps, for each ray of a
// grid of rays, the cumulative integral F(s_k) at every step boundary, and
// F(R) is interpolated linearly in s between boundaries; renderers interpolate
// between the grid's rays.
#include <vector>

#include <Eigen/Core>

namespace hsmap {

struct WaterBackscatterConfig {
  bool enabled = false;       // off: the water only attenuates
  double phase_g = 0.924;     // Henyey-Greenstein asymmetry, in [0, 0.99]
  double near_m = 0.05;       // the integral starts here (the camera's port), >= 0
  double max_range_m = 10.0;  // a ray that misses the seabed integrates to here, > near_m
  int steps = 256;            // quadrature intervals over [near_m, max_range_m]
};

// The Henyey-Greenstein phase function p(psi) in 1/sr.
double henyeyGreenstein(double cos_psi, double g);

// The lamps in the frame X of the camera whose rays are integrated.
struct BackscatterLamps {
  std::vector<Eigen::Vector3d> p_X;     // lamp centres
  std::vector<Eigen::Vector3d> axis_X;  // unit beam axes
  double power = 1.0;                   // P
  double beam_exponent = 2.0;           // n of B = cos^n
};

// What each channel of the table sums over wavelengths lambda_i: channel k is
// sum_i weight(k, i) * (the integral above at lambda_i, without I b), so that
// weight carries I(lambda_i) b(lambda_i) and any sensor response and d lambda.
struct BackscatterSpectrum {
  std::vector<double> attenuation_per_m;  // c(lambda_i)
  Eigen::MatrixXd weight;                 // channels x wavelengths
};

class WaterBackscatterTable {
 public:
  // rays_X: unit directions from the camera (the origin of X).
  WaterBackscatterTable(const WaterBackscatterConfig& config, const BackscatterLamps& lamps,
                        const std::vector<Eigen::Vector3d>& rays_X, const BackscatterSpectrum& spectrum);

  int channels() const { return channels_; }
  int rays() const { return rays_; }
  double maxRange() const { return near_ + span_; }
  // Where a range falls among the step boundaries: found once, used for
  // every ray that a renderer interpolates between.
  struct RangeIndex {
    int step = 0;    // boundary k below R
    float t = 0.0f;  // (R - s_k) / (s_k+1 - s_k)
  };
  // R clamped to [near_m, max_range_m].
  RangeIndex rangeIndex(double range_m) const;
  // out[k] += weight * F_k(R) of ray `ray`.
  void accumulate(int ray, RangeIndex range, float weight, float* out) const;
  void accumulate(int ray, double range_m, float weight, float* out) const {
    accumulate(ray, rangeIndex(range_m), weight, out);
  }

 private:
  double near_;
  double span_;
  int steps_;
  int channels_;
  int rays_;
  std::vector<float> cumulative_;  // [ray][boundary 0..steps][channel]
};

}  // namespace hsmap
