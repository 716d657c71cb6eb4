// Backscatter (optics.backscatter, water_backscatter.h) on a flat seabed
// below a level vehicle, checked against the model evaluated independently:
// the UHI's rendered backscatter (the cube with it minus the cube without it,
// no sensor noise) against the single-scattering integral of the contract's
// lamps, by a plain midpoint rule with 0.5 mm steps (the renderer uses a
// table over a quadratic grid of 256 steps and a grid of rays); it grows with
// turbidity, in the RGB frames too, and is nothing when off.
#include <cmath>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "core/geometry/pushbroom_camera.h"
#include "core/util/input_error.h"
#include "pipelines/simulate/simulation_config_yaml.h"
#include "tests/pipelines/simulate/flat_water.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

using testing::FlatWater;

// The model, independently: pi K(lambda) times the integral from near_m to R
// of sum_l B(theta_l) / r_l^2 exp(-c (r_l + s)) b p_HG(psi_l) ds, the lamps
// as survey.yaml states them (in C, moved to U).
double expectedBackscatterDn(const FlatWater& water, double K, double wavelength_nm,
                             const Eigen::Vector3d& ray_U, double range_m) {
  const WaterBackscatterConfig& model = water.config.optics.backscatter;
  const double c = waterAttenuationPerM(wavelength_nm, water.config.optics.turbidity);
  const double b = waterScatteringPerM(wavelength_nm, water.config.optics.turbidity);
  const double g = model.phase_g;
  const LightsConfig lights = water.lamps->lightsInCamera(water.config.calibration.T_B_C);
  const SE3d T_U_C = water.context.T_C_U.inverse();
  const double ds = 0.0005;
  double integral = 0.0;
  for (double s = model.near_m + ds / 2; s < range_m; s += ds) {
    const double step = std::min(ds, range_m - (s - ds / 2));
    const Eigen::Vector3d x = s * ray_U;
    for (const LampConfig& lamp : lights.lamps) {
      const Eigen::Vector3d v = x - T_U_C * lamp.p_C;
      const double r = v.norm();
      const double cos_beam = (T_U_C.q * lamp.axis_C).dot(v / r);
      if (cos_beam <= 0.0) continue;
      const double cos_psi = -ray_U.dot(v / r);
      const double phase = (1 - g * g) / (4 * std::numbers::pi * std::pow(1 + g * g - 2 * g * cos_psi, 1.5));
      integral += std::pow(cos_beam, water.config.optics.lamp_beam_exponent) / (r * r) *
                  std::exp(-c * (r + s)) * b * phase * step;
    }
  }
  return std::numbers::pi * K * integral;
}

TEST(WaterBackscatter, UhiLevelOnAFlatSeabedIsTheSingleScatteringIntegral) {
  const FlatWater clear(1.0, false);
  const FlatWater murky(1.0, true);
  const Eigen::MatrixXf backscatter = murky.uhiLine() - clear.uhiLine();
  const std::vector<double> K = murky.uhi->lampResponseDn();
  const PushbroomCamera camera(murky.config.uhi.camera);
  const SE3d T_B_U = murky.context.T_B_C * murky.context.T_C_U;
  const double seabed_z = murky.scene.vertices[0].z();
  double worst = 0.0;
  for (int s = 0; s < camera.samples(); s += 17) {
    const Eigen::Vector3d ray_U = camera.unproject(double(s))->normalized();
    const Eigen::Vector3d ray_B = T_B_U.q * ray_U;
    const double range = (seabed_z - T_B_U.t.z()) / ray_B.z();
    for (int band = 0; band < int(K.size()); band += 5) {
      const double expected = expectedBackscatterDn(murky, K[std::size_t(band)],
                                                    murky.wavelengths[std::size_t(band)], ray_U, range);
      ASSERT_GT(expected, 1.0) << "sample " << s << " band " << band;
      const double ratio = backscatter(band, s) / expected;
      worst = std::max(worst, std::abs(ratio - 1.0));
      EXPECT_NEAR(ratio, 1.0, 0.01) << "sample " << s << " band " << band << ": " << backscatter(band, s)
                                    << " DN rendered, " << expected << " DN expected";
    }
  }
  std::cout << "worst relative difference " << worst << "\n";
  std::cout << "556 nm backscatter at samples 0, 60, 120, 180, 239: " << backscatter(9, 0) << " "
            << backscatter(9, 60) << " " << backscatter(9, 120) << " " << backscatter(9, 180) << " "
            << backscatter(9, 239) << " DN; the seabed's DN at 120 without it: " << clear.uhiLine()(9, 120)
            << "\n";
  // truth/calibration.yaml's level is the principal sample's, at nadir.
  const std::vector<double> nominal = murky.uhi->nominalBackscatterDn();
  ASSERT_EQ(nominal.size(), K.size());
  const int centre = int(std::lround(camera.parameters().cx));
  for (std::size_t band = 0; band < K.size(); ++band) {
    EXPECT_NEAR(backscatter(Eigen::Index(band), centre) / nominal[band], 1.0, 0.01) << "band " << band;
  }
  std::cout << "backscatter_dn at 460/560/660 nm: " << nominal[3] << " " << nominal[9] << " " << nominal[15]
            << " (" << murky.wavelengths[3] << ", " << murky.wavelengths[9] << ", " << murky.wavelengths[15]
            << " nm)\n";
}

TEST(WaterBackscatter, GrowsWithTurbidityAndIsNothingWhenOff) {
  const FlatWater off(2.0, false);
  EXPECT_TRUE(off.uhi->nominalBackscatterDn().empty());
  EXPECT_EQ(off.uhi->backscatterDn(100.0, 2.0).norm(), 0.0f);
  const FlatWater once(1.0, true);
  const FlatWater twice(2.0, true);
  const std::vector<double> level1 = once.uhi->nominalBackscatterDn();
  const std::vector<double> level2 = twice.uhi->nominalBackscatterDn();
  for (std::size_t band = 0; band < level1.size(); ++band) {
    EXPECT_GT(level1[band], 0.0);
    EXPECT_GT(level2[band], 1.3 * level1[band]) << "band " << band;
  }
  // The RGB frames: brighter with backscatter, more so in murkier water; the
  // clear frame's pixels are the frame without backscatter's.
  const FlatWater rgb_off(1.0, false);
  const cv::Mat clear = rgb_off.rgbFrame();
  const double clear_mean = cv::mean(clear)[1];
  const double mean1 = cv::mean(once.rgbFrame())[1];
  const double mean2 = cv::mean(twice.rgbFrame())[1];
  std::cout << "RGB green mean: " << clear_mean << " DN without, " << mean1 << " with backscatter, " << mean2
            << " at turbidity 2 (whose seabed is darker)\n";
  EXPECT_GT(mean1, clear_mean + 1.0);
  const cv::Mat twice_clear = FlatWater(2.0, false).rgbFrame();
  EXPECT_GT(mean2 - cv::mean(twice_clear)[1], mean1 - clear_mean);
}

TEST(WaterBackscatter, SettingsAreReadStrictly) {
  testing::TempFolder folder("water_backscatter_yaml");
  const auto path = folder.path() / "sim.yaml";
  auto read = [&](const std::string& body) {
    std::ofstream(path) << "format: hsmap-simulation/1\npreset: tiny\n" << body;
    return readSimulationConfig(path);
  };
  EXPECT_FALSE(read("").optics.backscatter.enabled);
  const WaterBackscatterConfig on = read("optics: {backscatter: {}}\n").optics.backscatter;
  EXPECT_TRUE(on.enabled);
  EXPECT_EQ(on.phase_g, 0.924);
  EXPECT_EQ(on.steps, 256);
  const WaterBackscatterConfig set =
      read("optics: {backscatter: {phase_g: 0.8, near_m: 0.1, max_range_m: 6, steps: 64}}\n").optics.backscatter;
  EXPECT_EQ(set.phase_g, 0.8);
  EXPECT_EQ(set.near_m, 0.1);
  EXPECT_EQ(set.max_range_m, 6.0);
  EXPECT_EQ(set.steps, 64);
  try {
    read("optics: {backscatter: {phase_g: 1.5}}\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3, key optics.backscatter.phase_g"), std::string::npos) << e.what();
  }
  try {
    read("optics: {backscatter: {stepz: 10}}\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("optics.backscatter"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hsmap
