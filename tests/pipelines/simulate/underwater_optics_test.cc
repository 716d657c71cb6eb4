#include "pipelines/simulate/underwater_optics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pipelines/simulate/rgb_radiance_table.h"

namespace hsmap {
namespace {

TEST(WaterAttenuation, ClearInTheBlueGreenAndDarkInTheRed) {
  const double blue_green = waterAttenuationPerM(500.0, 1.0);
  EXPECT_GT(blue_green, 0.05);
  EXPECT_LT(blue_green, 0.3);
  EXPECT_GT(waterAttenuationPerM(700.0, 1.0), 3.0 * blue_green);
  // Increasing from the green minimum into the red and near infrared.
  for (double nm = 560.0; nm < 800.0; nm += 10.0) {
    EXPECT_LT(waterAttenuationPerM(nm, 1.0), waterAttenuationPerM(nm + 10.0, 1.0)) << nm;
  }
  // Turbidity adds dissolved matter and particles only.
  EXPECT_GT(waterAttenuationPerM(450.0, 3.0), waterAttenuationPerM(450.0, 1.0));
  EXPECT_GT(waterAttenuationPerM(450.0, 0.0), 0.0);
}

TEST(LampSpectrum, LightsEveryBandOfTheUhi) {
  for (double nm = 400.0; nm <= 800.0; nm += 5.0) EXPECT_GT(lampSpectrum(nm), 0.02) << nm;
}

TEST(RgbResponse, EachChannelPeaksInItsOwnBand) {
  EXPECT_GT(rgbResponse(0, 610.0), rgbResponse(0, 530.0));
  EXPECT_GT(rgbResponse(1, 535.0), rgbResponse(1, 610.0));
  EXPECT_GT(rgbResponse(2, 460.0), rgbResponse(2, 535.0));
}

SimulatedOpticsConfig optics() {
  SimulatedOpticsConfig config;
  config.lamp_separation_m = 0.6;
  config.lamp_forward_m = 0.0;
  config.lamp_beam_exponent = 0.0;  // isotropic lamps: pure inverse-square and cosine law
  return config;
}

TEST(LampRig, InverseSquareAndCosineLaws) {
  RigidTransformConfig T_B_C;  // camera at the body origin
  const LampRig rig(optics(), T_B_C);
  const SE3d T_W_B;
  const Eigen::Vector3d up(0.0, 0.0, -1.0);
  const LampLighting at2 = rig.light(T_W_B, Eigen::Vector3d(0.0, 0.0, 2.0), up, nullptr);
  const LampLighting at4 = rig.light(T_W_B, Eigen::Vector3d(0.0, 0.0, 4.0), up, nullptr);
  ASSERT_EQ(at2.count, 2);
  const double r2 = std::hypot(2.0, 0.3), r4 = std::hypot(4.0, 0.3);
  EXPECT_NEAR(at2.path_length[0], r2, 1e-12);
  EXPECT_NEAR(at2.weight[0], (2.0 / r2) / (r2 * r2), 1e-12);
  EXPECT_NEAR(at4.weight[1], (4.0 / r4) / (r4 * r4), 1e-12);
  // A surface facing away from the lamps is not lit.
  const LampLighting away =
      rig.light(T_W_B, Eigen::Vector3d(0.0, 0.0, 2.0), Eigen::Vector3d(0.0, 0.0, 1.0), nullptr);
  EXPECT_EQ(away.weight[0], 0.0);
  EXPECT_EQ(away.weight[1], 0.0);
}

TEST(LampRig, ShadowsComeFromTheScene) {
  RigidTransformConfig T_B_C;
  const LampRig rig(optics(), T_B_C);
  // A small plate 1 m above the point, under the starboard lamp (east +0.3 m) only.
  const std::vector<Eigen::Vector3d> vertices{{-0.1, 0.2, 1.0}, {0.1, 0.2, 1.0}, {0.1, 0.5, 1.0},
                                              {-0.1, 0.5, 1.0}};
  const std::vector<Eigen::Vector3i> triangles{{0, 1, 2}, {0, 2, 3}};
  const MeshRayCaster plate(vertices, triangles);
  const Eigen::Vector3d p(0.0, 0.3, 2.0);
  const LampLighting lit = rig.light(SE3d(), p, Eigen::Vector3d(0, 0, -1), nullptr);
  const LampLighting shadowed = rig.light(SE3d(), p, Eigen::Vector3d(0, 0, -1), &plate);
  EXPECT_GT(lit.weight[1], 0.0);
  EXPECT_EQ(shadowed.weight[1], 0.0);                // starboard lamp blocked
  EXPECT_DOUBLE_EQ(shadowed.weight[0], lit.weight[0]);  // port lamp clear
}

TEST(RgbRadianceTable, MatchesDirectSpectralIntegrationAndDecaysWithPath) {
  const RgbRadianceTable table(1.0);
  // Direct integration of the flat-reflectance column at an off-grid path length.
  const double path = 3.1234;
  for (int k = 0; k < 3; ++k) {
    double direct = 0.0;
    for (double nm = 380.0; nm <= 720.0; nm += 5.0) {
      direct += rgbResponse(k, nm) * lampSpectrum(nm) * 5.0 *
                std::exp(-waterAttenuationPerM(nm, 1.0) * path);
    }
    EXPECT_NEAR(table.at(path)(k, kEndmemberCount), direct, 1e-4 * direct) << k;
    EXPECT_LT(table.at(path + 1.0)(k, kEndmemberCount), table.at(path)(k, kEndmemberCount));
  }
  // Red fades fastest with distance in water.
  const auto near = table.at(1.0), far = table.at(6.0);
  EXPECT_LT(far(0, kEndmemberCount) / near(0, kEndmemberCount),
            far(1, kEndmemberCount) / near(1, kEndmemberCount));
}

}  // namespace
}  // namespace hsmap
