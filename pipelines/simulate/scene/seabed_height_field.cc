#include "pipelines/simulate/scene/seabed_height_field.h"

#include <cmath>
#include <random>

#include "pipelines/simulate/scene/procedural_noise.h"
#include "pipelines/simulate/scene/random_draw.h"

namespace hsmap {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Sizes of the layers (metres). See the header for what each preset holds.
constexpr double kFlatRoughnessM = 0.010;
constexpr double kRuggedRoughnessM = 0.028;
constexpr double kFineRoughnessM = 0.0015;
constexpr double kUndulationM = 0.45;
constexpr double kCrestHeightM = 0.18;

}  // namespace

SeabedHeightField::SeabedHeightField(const SeabedSceneConfig& config) : config_(config) {
  config_.validate();
  std::mt19937_64 rng(config.seed);
  // Seeds first, then the feature parameters, always in the same order, so
  // every preset of one seed shares its roughness and undulation.
  roughness_seed_ = rng();
  fine_seed_ = rng();
  undulation_seed_ = rng();
  scarp_seed_ = rng();
  face_seed_ = rng();
  ridge_seed_ = rng();
  crest_seed_ = rng();
  crest_mask_seed_ = rng();

  const bool rugged = config.terrain == TerrainPreset::rugged;
  roughness_amplitude_m_ = rugged ? kRuggedRoughnessM : kFlatRoughnessM;
  undulation_amplitude_m_ = config.terrain == TerrainPreset::flat ? 0.0 : kUndulationM;

  const double north_length_m = config.north_max_m - config.north_min_m;
  scarp_north_m_ = config.north_min_m + north_length_m * uniformDraw(rng, 0.36, 0.40);
  scarp_skew_ = std::tan(uniformDraw(rng, -15.0, 15.0) * kPi / 180.0);
  scarp_rise_m_ = uniformDraw(rng, 1.1, 1.3);
  // A smoothstep profile is steepest in its middle, at 1.5 rise / width; aim
  // that at tan(60 deg) (ledges on the face make parts of it steeper).
  scarp_width_m_ = 1.5 * scarp_rise_m_ / std::tan(60.0 * kPi / 180.0);

  ridge_north_m_ = config.north_min_m + north_length_m * uniformDraw(rng, 0.70, 0.74);
  const double ridge_angle = uniformDraw(rng, 20.0, 35.0) * kPi / 180.0;  // from the east axis
  ridge_cos_ = std::cos(ridge_angle);
  ridge_sin_ = std::sin(ridge_angle);
  ridge_height_m_ = uniformDraw(rng, 0.75, 0.95);
  // (1 - u^2)^2 is steepest at u = 1/sqrt(3) with slope 1.54 height / half width:
  // aim that at tan(50 deg).
  ridge_half_width_m_ = 1.54 * ridge_height_m_ / std::tan(50.0 * kPi / 180.0);

  // No random draws here: a slope leaves every other layer as it was.
  has_slope_ = config.slope_deg > 0.0;
  if (has_slope_) {
    // The downhill direction in the build frame, which W turned by -heading.
    const double direction = (config.slope_direction_deg - config.heading_deg) * kPi / 180.0;
    const double gradient = std::tan(config.slope_deg * kPi / 180.0);
    slope_north_ = gradient * std::cos(direction);
    slope_east_ = gradient * std::sin(direction);
  }
}

double SeabedHeightField::roughness(double north_m, double east_m) const {
  static constexpr FbmParameters kRoughness{1.0 / 0.10, 3, 1.97, 0.5};
  const double fine = gradientNoise2(fine_seed_, north_m / 0.025, east_m / 0.025);
  return roughness_amplitude_m_ * fbm2(roughness_seed_, north_m, east_m, kRoughness) +
         kFineRoughnessM * fine;
}

double SeabedHeightField::undulation(double north_m, double east_m) const {
  static constexpr FbmParameters kUndulation{1.0 / 4.5, 3, 2.03, 0.45};
  return undulation_amplitude_m_ * fbm2(undulation_seed_, north_m, east_m, kUndulation);
}

double SeabedHeightField::scarp(double north_m, double east_m) const {
  // The face line wanders +-0.4 m in plan around a straight skewed line.
  const double wander = 0.55 * gradientNoise2(scarp_seed_, east_m / 2.5, 0.5);
  const double across = north_m - (scarp_north_m_ + scarp_skew_ * east_m + wander);
  const double t = across / scarp_width_m_ + 0.5;
  if (t <= 0.0) return 0.0;
  if (t >= 1.0) return scarp_rise_m_;
  // Ledges: noise that is strongest mid-face and fades out towards its top and
  // foot with zero slope, so the face joins the flats without a kink.
  static constexpr FbmParameters kLedges{1.0 / 0.35, 3, 2.1, 0.5};
  const double bell = 4.0 * t * (1.0 - t);
  const double on_face = bell * bell;
  return scarp_rise_m_ * t * t * (3.0 - 2.0 * t) +
         on_face * 0.12 * fbm2(face_seed_, north_m, east_m, kLedges);
}

double SeabedHeightField::ridge(double north_m, double east_m) const {
  const double across = (north_m - ridge_north_m_) * ridge_cos_ - east_m * ridge_sin_;
  const double u = across / ridge_half_width_m_;
  if (std::abs(u) >= 1.0) return 0.0;
  const double along = (north_m - ridge_north_m_) * ridge_sin_ + east_m * ridge_cos_;
  // The crest height varies by +-15% along the ridge.
  const double height =
      ridge_height_m_ * (1.0 + 0.3 * gradientNoise2(ridge_seed_, along / 3.0, 0.5));
  const double v = 1.0 - u * u;
  return height * v * v;
}

double SeabedHeightField::crests(double north_m, double east_m) const {
  const double mask =
      smoothStep(0.0, 0.25, gradientNoise2(crest_mask_seed_, north_m / 7.0, east_m / 7.0));
  if (mask == 0.0) return 0.0;
  // Crests run along the zero lines of n (|grad n| is about 0.5 per metre):
  // c = 1 - |n| / 0.09 is 1 on the line and 0 about 0.18 m to each side. The
  // smoothstep of c rounds the crest (zero slope where |n| has its kink) and
  // keeps the flanks near 55 degrees at the steepest.
  const double n = gradientNoise2(crest_seed_, north_m / 1.6, east_m / 1.6);
  const double c = 1.0 - std::abs(n) / 0.09;
  if (c <= 0.0) return 0.0;
  return kCrestHeightM * mask * c * c * (3.0 - 2.0 * c);
}

double SeabedHeightField::elevation(double north_m, double east_m) const {
  double h = roughness(north_m, east_m);
  if (config_.terrain == TerrainPreset::flat) return h;
  h += undulation(north_m, east_m);
  if (config_.terrain == TerrainPreset::rugged) {
    h += scarp(north_m, east_m) + ridge(north_m, east_m) + crests(north_m, east_m);
  }
  return h;
}

}  // namespace hsmap
