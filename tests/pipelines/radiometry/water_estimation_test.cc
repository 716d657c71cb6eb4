#include "pipelines/radiometry/water_estimation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hsmap {
namespace {

// A synthetic patch: a flat seabed (normal up, W's z down), the UHI and two
// lamps 0.3 m to either side, pointing down, seeing each seabed point from
// several altitudes and across-track offsets (overlapping lanes, the
// altitude changing), with the contract's model and known c, beam,
// backscatter and reflectance, 2 % multiplicative noise and 1 DN read noise.
struct Truth {
  std::vector<double> c{0.10, 0.15, 0.30, 0.60, 1.00};
  std::vector<double> k{4000, 6000, 5000, 3000, 2000};
  std::vector<double> backscatter{8, 6, 4, 2, 1};
  double beam[2] = {-3.0, -0.5};
  std::vector<double> wavelengths_nm{450, 500, 550, 600, 650};
};

std::vector<LampPath> pathsFor(double x, double altitude) {
  const Eigen::Vector3d p(x, 0.0, altitude), n(0.0, 0.0, -1.0), axis(0.0, 0.0, 1.0);
  std::vector<LampPath> paths;
  for (double side : {-0.3, 0.3}) {
    const Eigen::Vector3d lamp(side, -0.3, 0.0);
    const Eigen::Vector3d to_lamp = lamp - p;
    LampPath path;
    path.range_m = to_lamp.norm();
    path.cos_incidence = n.dot(to_lamp) / path.range_m;
    path.off_axis_rad = std::acos(axis.dot(-to_lamp / path.range_m));
    paths.push_back(path);
  }
  return paths;
}

RadiometricObservations synthesize(const Truth& truth, bool varied_geometry, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> reflectance(0.05, 0.6), offset(-0.8, 0.8), altitude(1.2, 2.4);
  std::normal_distribution<double> normal(0.0, 1.0);
  RadiometricObservations observations;
  observations.bands = int(truth.c.size());
  observations.points = 60;
  for (int p = 0; p < observations.points; ++p) {
    std::vector<double> rho;
    for (std::size_t b = 0; b < truth.c.size(); ++b) rho.push_back(reflectance(rng));
    const double x0 = offset(rng), h0 = 1.6;
    for (int i = 0; i < 12; ++i) {
      RadiometricObservation o;
      o.point = p;
      const double x = varied_geometry ? offset(rng) : x0;
      const double h = varied_geometry ? altitude(rng) : h0;
      o.uhi_range_m = std::hypot(x, h);
      o.lamps = pathsFor(x, h);
      for (std::size_t b = 0; b < truth.c.size(); ++b) {
        const double dn = truth.k[b] * rho[b] * lampIllumination(o.lamps, o.uhi_range_m, truth.c[b], truth.beam) +
                          truth.backscatter[b];
        o.dn.push_back(float(dn * (1.0 + 0.02 * normal(rng)) + normal(rng)));
      }
      observations.items.push_back(std::move(o));
    }
  }
  return observations;
}

TEST(WaterEstimation, RecoversAttenuationBeamAndBackscatterWithinTheirSigma) {
  const Truth truth;
  WaterEstimationOptions options;
  options.relative_noise = 0.02;
  options.initial_attenuation_per_m = 0.4;  // a perturbed start: every band off by 0.3 /m or more but one
  const WaterEstimationReport report = estimateWater(synthesize(truth, true, 7), truth.k, truth.wavelengths_nm, options);
  ASSERT_TRUE(report.solve.usable) << report.solve.toString();
  ASSERT_TRUE(report.covariance_computed);
  ASSERT_TRUE(report.backscatter_estimated);
  const WaterEstimate& water = report.water;
  for (std::size_t b = 0; b < truth.c.size(); ++b) {
    ASSERT_TRUE(water.attenuation_sigma_per_m[b].has_value());
    const double sigma = *water.attenuation_sigma_per_m[b];
    // Determined (a sigma that could hide a wrong c would pass anything)...
    EXPECT_LT(sigma, 0.02) << "band " << b;
    // ... and right within 4 of its sigmas.
    EXPECT_LT(std::abs(water.attenuation_per_m[b] - truth.c[b]), 4.0 * sigma) << "band " << b;
    ASSERT_TRUE(water.backscatter_sigma_dn[b].has_value());
    EXPECT_LT(std::abs(water.backscatter_dn[b] - truth.backscatter[b]), 4.0 * *water.backscatter_sigma_dn[b] + 1e-9)
        << "band " << b;
    EXPECT_LT(*water.backscatter_sigma_dn[b], 3.0) << "band " << b;
  }
  for (int i = 0; i < 2; ++i) {
    ASSERT_TRUE(water.beam_sigma[std::size_t(i)].has_value());
    EXPECT_LT(std::abs(water.beam[std::size_t(i)] - truth.beam[i]), 4.0 * *water.beam_sigma[std::size_t(i)]);
    EXPECT_LT(*water.beam_sigma[std::size_t(i)], 0.5);
  }
  // The beam off the axis, where the patch sees it (up to ~35 deg): within 2 %.
  for (double theta : {0.2, 0.4, 0.6}) {
    EXPECT_NEAR(lampBeam(theta, water.beam.data()) / lampBeam(theta, truth.beam), 1.0, 0.02) << theta;
  }
  for (const std::string& warning : water.warnings) ADD_FAILURE() << "unexpected warning: " << warning;
}

TEST(WaterEstimation, WarnsWhenEveryPointIsSeenFromOneGeometry) {
  // Each point always at the same range and angles (one pass at a constant
  // altitude over a flat seabed): its reflectance absorbs everything.
  const Truth truth;
  WaterEstimationOptions options;
  options.relative_noise = 0.02;
  const WaterEstimationReport report = estimateWater(synthesize(truth, false, 11), truth.k, truth.wavelengths_nm, options);
  bool named = false;
  for (const std::string& warning : report.water.warnings) {
    named = named || warning.find("does not determine c(λ)") != std::string::npos;
  }
  EXPECT_TRUE(named) << report.summary({});
}

TEST(WaterEstimation, RejectsAResponseOfTheWrongLength) {
  const Truth truth;
  EXPECT_THROW(estimateWater(synthesize(truth, true, 3), {1.0, 2.0}, truth.wavelengths_nm), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
