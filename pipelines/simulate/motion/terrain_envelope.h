#pragma once
// TerrainEnvelope: the seabed depth a vehicle's altitude is held above, as a
// smooth function of arc length s along a LanePath.
//
// A vehicle that kept its altitude above the seabed point directly below it
// would dive into every gap and hit the side of every boulder; real vehicles
// follow a smoothed, upper envelope of the terrain ahead. Here, in W (z down,
// so "highest" is the smallest z):
//   1. sample the seabed on `cross_samples` lines parallel to the path,
//      offsets evenly spread over [-radius, +radius] across track, every ds
//      along it (ds >= min_spacing_m, enlarged so that the number of
//      seabed_z calls stays within max_queries);
//   2. upper envelope: M(s_i) = min z over all samples with |s_j - s_i| <= radius;
//   3. smoothing: Z(s_i) = Hann-weighted mean of M over |s_j - s_i| < smoothing_half_width_m;
//   4. Z(s) is the natural cubic spline (C2) through the Z(s_i).
// Since the smoothing window is no wider than the envelope window, every M
// averaged into Z(s_i) is <= the seabed z of every sample within radius of
// s_i across and along track, so Z(s_i) <= seabed z at the sample points
// near s_i: the vehicle at Z - altitude is never closer to the sampled
// seabed than `altitude`.
//
// seabed_z may be expensive (a ray cast). A non-finite value means "no
// surface there" (e.g. outside the scene) and is skipped; a window with no
// finite sample at all is an error.

#include <functional>
#include <vector>

#include "pipelines/simulate/motion/lane_path.h"
#include "pipelines/simulate/motion/natural_cubic_spline.h"

namespace hsmap {

struct TerrainEnvelopeOptions {
  double radius_m = 1.0;               // half-width of the envelope window, along and across track
  double smoothing_half_width_m = 1.0; // half-width of the Hann window; must be <= radius_m
  int cross_samples = 9;               // sample lines across track (odd: one on the path)
  double min_spacing_m = 0.05;         // along-track sample spacing, at least
  int max_queries = 20000;             // budget of seabed_z calls

  // Throws std::invalid_argument naming the first bad option.
  void validate() const;
};

class TerrainEnvelope {
 public:
  // Throws std::invalid_argument for invalid options or when a window holds
  // no finite seabed sample.
  TerrainEnvelope(const LanePath& path,
                  const std::function<double(double north, double east)>& seabed_z,
                  const TerrainEnvelopeOptions& options = {});

  // Smoothed envelope z_W (down, metres) at arc length s (linear beyond the ends).
  double z(double s) const { return spline_.value(s); }
  double dzds(double s) const { return spline_.derivative(s); }

  // Number of seabed_z calls made by the constructor.
  int queries() const { return queries_; }

 private:
  static NaturalCubicSpline build(const LanePath& path,
                                  const std::function<double(double, double)>& seabed_z,
                                  const TerrainEnvelopeOptions& options, int* queries);

  int queries_ = 0;
  NaturalCubicSpline spline_;
};

}  // namespace hsmap
