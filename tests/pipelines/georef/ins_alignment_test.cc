#include "pipelines/georef/ins_alignment.h"

#include <gtest/gtest.h>

#include "tests/pipelines/georef/georef_test_scene.h"

namespace hsmap {
namespace {

using namespace georef_testing;

// The front-end's frames at 30 fps, expressed in F.
CameraTrajectory visionInF() {
  const Sim3 S_F_W = trueS_W_F().inverse();
  std::vector<double> times;
  std::vector<SE3d> poses;
  for (int i = 0; i <= 900; ++i) {
    times.push_back(i / 30.0);
    poses.push_back(S_F_W.transformPose(trueCamera(times.back())));
  }
  return CameraTrajectory(times, poses, nullptr, mountingT_B_C(), 0.25);
}

// With INS attitude the rotation is the attitudes' (0.05-0.2 degree noise).
// Without it, the level, along-track attitude stands in: the vehicle's 2
// degree roll and 1.5 degree pitch swings and the heading smoothed over
// 20 s leave the start a few degrees off, which the bundle adjustment's
// positions then correct (georef_bundle_adjuster_test.cc).
// The scene's INS noise: 0.1 m horizontal, 2 cm depth, attitude exact (as
// stated: 0.01 degree).
InsNoise sceneNoise() {
  InsNoise noise;
  noise.sigma_horizontal_m = 0.1;
  noise.sigma_depth_m = 0.02;
  noise.sigma_attitude_rad = Eigen::Vector3d::Constant(0.01 * M_PI / 180.0);
  return noise;
}

void expectRecovered(const InsAlignment& alignment, bool attitude) {
  const Sim3& S = alignment.S_W_F;
  const Sim3& truth = trueS_W_F();
  EXPECT_NEAR(S.scale() / truth.scale(), 1.0, 0.01);
  EXPECT_LT(angleDeg(S.rotation(), truth.rotation()), attitude ? 0.5 : 5.0);
  // Where the map lands: the trajectory's centre within centimetres.
  const Eigen::Vector3d p_F = truth.inverse().apply(trueCamera(15.0).t);
  EXPECT_LT((S.apply(p_F) - trueCamera(15.0).t).norm(), attitude ? 0.05 : 0.1);
}

TEST(InsAlignment, RecoversTheSimilarityAndLeavesOutAFixThatJumpedMetres) {
  for (bool attitude : {true, false}) {
    SCOPED_TRACE(attitude ? "with INS attitude" : "without INS attitude");
    const InsBodyTrack ins(insFixes(0.1, 0.02, 3, {{12, Eigen::Vector3d(4.0, -3.0, 0.0)}}), attitude);
    const InsAlignment alignment = alignVisionToIns(visionInF(), ins, mountingT_B_C(), sceneNoise());
    ASSERT_EQ(alignment.paired_fixes.size(), 31u);
    EXPECT_EQ(alignment.inlier_count, 30);
    EXPECT_FALSE(alignment.inliers[12]);
    EXPECT_NEAR(alignment.residuals_m[12], 5.0, 0.3);
    EXPECT_LT(alignment.rms_m, attitude ? 0.25 : 0.4);
    EXPECT_EQ(alignment.rotation_from,
              attitude ? "INS attitude" : "level, along-track attitude (no INS attitude)");
    expectRecovered(alignment, attitude);
  }
}

TEST(InsAlignment, NeedsThreeFixesWithinVision) {
  const InsBodyTrack ins(insFixes(0.1, 0.02, 3), true);
  const CameraTrajectory short_vision({10.2, 10.3, 10.4, 11.3},
                                      {trueCamera(10.2), trueCamera(10.3), trueCamera(10.4), trueCamera(11.3)},
                                      nullptr, mountingT_B_C(), 0.25);
  try {
    alignVisionToIns(short_vision, ins, mountingT_B_C(), sceneNoise());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(),
                 "cannot geo-reference: only 0 INS fixes fall within the time span that vision "
                 "posed (need at least 3)");
  }
}

}  // namespace
}  // namespace hsmap
