#pragma once
// Marine snow (optics.marine_snow): particles suspended in the water in front
// of the RGB camera, lit by the lamps, a new random set in every frame. They
// are not part of the scene (truth/scene.ply) and must never become
// landmarks; the UHI does not see them.
//
// Placement. For frame k, the particles are drawn from the seed and k alone:
// their number is Poisson with mean density_per_m3 x V, V the volume of the
// camera's pinhole frustum between the depths near_m and max_range_m along
// its axis, V = (width / fx) (height / fy) (max^3 - near^3) / 3; each is
// uniform in that volume (depth z with density ~ z^2, image point uniform)
// at the frame's camera pose, so it stays fixed in W while the shutter is
// open (motion blur streaks it); its diameter is log-uniform in
// [diameter_min_mm, diameter_max_mm].
//
// Appearance. A particle behind the scene (its ray from the camera hits the
// scene first) is hidden. Otherwise it is a Lambertian reflector of
// reflectance `albedo` facing the lamps: its linear RGB, as the seabed's
// (rgb_renderer.h) without cos(incidence), is
//   albedo * sum_l P B(theta_l) / r_l^2 * T_k(r_l + d),
// T the radiance table's flat unit reflectance through a water path r_l + d
// (d: camera to particle), spread over the image as a Gaussian dot whose sum
// is that value times the particle's area in pixels, pi (f D / 2 z)^2, so a
// particle smaller than a pixel dims instead of vanishing. The camera is
// focused on the seabed at the nominal altitude z_f; a particle at depth z is
// out of focus by the thin-lens blur circle c = A f |1/z - 1/z_f| pixels (A
// the lens aperture), and the dot's sigma is
// sqrt((f D / 4 z)^2 + (c / 4)^2 + 0.3^2) pixels.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/geometry/camera_parameters.h"
#include "core/geometry/se3.h"

namespace hsmap {

struct MarineSnowConfig {
  bool enabled = false;
  double density_per_m3 = 100.0;  // particles per cubic metre of water, >= 0
  double diameter_min_mm = 0.5;   // marine snow: aggregates of 0.5 mm and more
  double diameter_max_mm = 3.0;
  double near_m = 0.2;            // the nearest particle depth in front of the camera
  double max_range_m = 4.0;       // the farthest (beyond, the lamps light little)
  double albedo = 0.6;
  double aperture_mm = 5.0;       // lens aperture diameter: how blurred near particles are
};

struct SnowParticle {
  Eigen::Vector3d p_W;
  double diameter_m = 0.0;
};

// The frustum volume V (m^3) in which the particles are drawn.
double marineSnowVolume(const MarineSnowConfig& config, const PinholeRadtanParameters& camera);

// Frame k's particles seen from T_W_C (its pose at the frame's time).
std::vector<SnowParticle> sampleMarineSnow(const MarineSnowConfig& config,
                                           const PinholeRadtanParameters& camera, const SE3d& T_W_C,
                                           std::uint64_t frame_seed);

}  // namespace hsmap
