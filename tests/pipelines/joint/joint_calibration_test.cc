// jointCalibration (pipelines/joint/joint_solution.h): the lever arm's
// 1-sigma carries what the map's scale uncertainty moves it by, and says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include <cmath>

#include "core/geometry/so3.h"
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

// A similarity moves the spline exactly (pose by pose), the landmarks, and
// the lever arm by its scale: the tie points measured it in the map's units.
TEST(JointCalibration, EstimatedUhiIntrinsicsGoToUhiCameraWithTheirSigmasAndWarnings) {
  JointResult joint = solvedLeverArm();
  EXPECT_FALSE(jointCalibration(joint, 2).uhi_camera);
  joint.uhi_intrinsics = std::array<double, 4>{1515.2, 957.1, 0.021, -0.004};
  joint.uhi_intrinsics_sigma = std::array<double, 4>{0.8, 0.1, 0.0007, 0.0};
  joint.inseparable_intrinsics = {"uhi_camera.cx cannot be separated from T_C_U's rotation about U's y"};
  const RunCalibration calibration = jointCalibration(joint, 2);
  ASSERT_TRUE(calibration.uhi_camera);
  EXPECT_EQ(calibration.uhi_camera->f, 1515.2);
  EXPECT_EQ(calibration.uhi_camera->cx, 957.1);
  EXPECT_EQ(calibration.uhi_camera->distortion, (std::array<double, 2>{0.021, -0.004}));
  EXPECT_EQ(calibration.uhi_camera->sigma.f, 0.8);
  EXPECT_EQ(calibration.uhi_camera->sigma.distortion, (std::array<double, 2>{0.0007, 0.0}));
  EXPECT_NE(std::find(calibration.warnings.begin(), calibration.warnings.end(), joint.inseparable_intrinsics[0]),
            calibration.warnings.end());
}

TEST(JointSurfaceFrame, ASimilarityMovesTheSplinePoseByPoseAndScalesTheLeverArm) {
  std::vector<SE3d> control_points;
  for (int i = 0; i < 8; ++i) {
    control_points.emplace_back(expSO3(Eigen::Vector3d(0.02 * i, -0.01 * i, 0.3 + 0.05 * i)),
                                Eigen::Vector3d(0.4 * i, 0.1 * i * i, 38.0 + 0.05 * i));
  }
  JointResult joint = solvedLeverArm();
  joint.spline = SE3Splined(10.0, 0.5, control_points);
  joint.landmarks_W = {{7, Eigen::Vector3d(1.0, 2.0, 40.0)}};
  const Sim3 G(1.018, expSO3(Eigen::Vector3d(0.001, -0.002, 0.01)), Eigen::Vector3d(0.3, -0.2, -0.7));
  const JointResult moved = inSurfaceFrame(joint, G);
  for (double t = joint.spline.validBegin(); t <= joint.spline.validEnd(); t += 0.05) {
    const SE3d expected = G.transformPose(joint.spline.pose(t));
    const SE3d got = moved.spline.pose(t);
    EXPECT_LT((got.t - expected.t).norm(), 1e-10) << "t = " << t;
    EXPECT_LT(got.q.angularDistance(expected.q), 1e-10) << "t = " << t;
  }
  EXPECT_LT((moved.landmarks_W[0].second - G.apply(Eigen::Vector3d(1.0, 2.0, 40.0))).norm(), 1e-12);
  EXPECT_LT((moved.T_C_U.t - 1.018 * joint.T_C_U.t).norm(), 1e-15);
  EXPECT_LT(moved.T_C_U.q.angularDistance(joint.T_C_U.q), 1e-15);

  // And ontoSurfaceFrame finds that similarity back from the frames.
  std::vector<TimedPose> frames;
  for (double t = joint.spline.validBegin(); t <= joint.spline.validEnd(); t += 0.1) {
    frames.push_back({t, joint.spline.pose(t)});
  }
  const Sim3 found = ontoSurfaceFrame(joint.spline, moved.spline, frames);
  EXPECT_NEAR(found.scale(), 1.018, 1e-9);
  EXPECT_LT(found.rotation().angularDistance(G.rotation()), 1e-9);
  EXPECT_LT((found.translation() - G.translation()).norm(), 1e-7);
}

}  // namespace
}  // namespace hsmap
