// jointCalibration (pipelines/joint/joint_solution.h): the lever arm's
// 1-sigma carries what the map's scale uncertainty moves it by, and says so.
#include <gtest/gtest.h>

#include <cmath>

#include "pipelines/joint/joint_solution.h"

namespace hsmap {
namespace {

JointResult solvedLeverArm() {
  JointResult joint;
  joint.solved = true;
  joint.T_C_U = SE3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.02, -0.15, 0.01));
  joint.sigma_rotation_deg = Eigen::Vector3d(0.01, 0.01, 0.02);
  joint.sigma_translation_m = Eigen::Vector3d(0.0014, 0.0039, 0.0005);
  joint.time_offset_sigma_s = 0.0001;
  return joint;
}

TEST(JointCalibration, TranslationSigmaAddsTheMapScaleUncertaintyAlongTheLeverArm) {
  MapPlacement placement;
  placement.fixes = 12;
  placement.scale_sigma = 0.04;  // 4 %: a lever arm of 15 cm is then known to 6 mm along y
  const RunCalibration with = jointCalibration(solvedLeverArm(), 2, placement);
  ASSERT_TRUE(with.sigma_translation_m.has_value());
  const Eigen::Vector3d sigma = *with.sigma_translation_m;
  EXPECT_NEAR(sigma.x(), std::hypot(0.0014, 0.04 * 0.02), 1e-12);
  EXPECT_NEAR(sigma.y(), std::hypot(0.0039, 0.04 * 0.15), 1e-12);
  EXPECT_NEAR(sigma.z(), std::hypot(0.0005, 0.04 * 0.01), 1e-12);
  // The rotation and d do not scale with the map.
  EXPECT_EQ(*with.sigma_rotation_deg, *solvedLeverArm().sigma_rotation_deg);
  bool said = false;
  for (const std::string& warning : with.warnings) {
    said = said || warning.find("includes the map's scale uncertainty (4.00 %") != std::string::npos;
  }
  EXPECT_TRUE(said);

  const RunCalibration without = jointCalibration(solvedLeverArm(), 2);
  EXPECT_EQ(*without.sigma_translation_m, *solvedLeverArm().sigma_translation_m);
}

}  // namespace
}  // namespace hsmap
