#include "pipelines/georef/camera_trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// A vehicle moving north at 0.5 m/s and turning slowly, its INS exact.
SE3d trueBody(double t) {
  return SE3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.02 * t, Eigen::Vector3d::UnitZ())),
              Eigen::Vector3d(0.5 * t, 0.1 * std::sin(t), 8.0));
}

const SE3d kT_B_C(Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())),
                  Eigen::Vector3d(0.5, 0.0, 0.3));

InsBodyTrack exactIns(double offset_north_m) {
  std::vector<InsBodyFix> fixes;
  for (int i = 0; i <= 20; ++i) {
    InsBodyFix fix;
    fix.t = double(i);
    const SE3d T = trueBody(fix.t);
    fix.p_W_B = T.t + Eigen::Vector3d(offset_north_m, 0, 0);
    fix.q_W_B = T.q;
    fixes.push_back(fix);
  }
  return InsBodyTrack(fixes, true);
}

TEST(CameraTrajectory, InterpolatesVisionAndReturnsPosedFramesExactly) {
  const InsBodyTrack ins = exactIns(0.0);
  std::vector<double> times = {2.0, 2.1, 2.2};
  std::vector<SE3d> poses;
  for (double t : times) poses.push_back(trueBody(t) * kT_B_C);
  const CameraTrajectory trajectory(times, poses, &ins, kT_B_C, 0.25);
  const TimedCameraPose at = trajectory.at(2.1);
  EXPECT_EQ(at.source, PoseSource::vision);
  EXPECT_EQ(at.T_W_C.t, poses[1].t);
  EXPECT_EQ(trajectory.at(2.15).source, PoseSource::vision);
  EXPECT_TRUE(trajectory.visionCovers(2.2));
  EXPECT_FALSE(trajectory.visionCovers(2.21));
}

TEST(CameraTrajectory, BridgesAGapWithTheInsAndMeetsVisionAtBothEdges) {
  // The INS is 0.3 m north of the truth; vision (exact) has a 3 s gap.
  const InsBodyTrack ins = exactIns(0.3);
  std::vector<double> times = {1.0, 1.1, 4.1, 4.2};
  std::vector<SE3d> poses;
  for (double t : times) poses.push_back(trueBody(t) * kT_B_C);
  const CameraTrajectory trajectory(times, poses, &ins, kT_B_C, 0.25);
  // Inside the gap the bridge carries the INS's motion and removes its offset.
  for (double t : {1.5, 2.6, 3.9}) {
    const TimedCameraPose at = trajectory.at(t);
    EXPECT_EQ(at.source, PoseSource::ins_bridged) << t;
    // The INS's linear interpolation between 1 Hz fixes is the only error left.
    EXPECT_LT((at.T_W_C.t - (trueBody(t) * kT_B_C).t).norm(), 0.03) << t;
  }
  EXPECT_LT((trajectory.at(1.1 + 1e-9).T_W_C.t - poses[1].t).norm(), 1e-6);
  // Beyond the last frame the INS continues from the last offset.
  const TimedCameraPose after = trajectory.at(6.0);
  EXPECT_EQ(after.source, PoseSource::ins_bridged);
  EXPECT_LT((after.T_W_C.t - (trueBody(6.0) * kT_B_C).t).norm(), 0.03);
  // Beyond the INS as well: held, never extrapolated.
  const TimedCameraPose held = trajectory.at(25.0);
  EXPECT_EQ(held.source, PoseSource::held);
  EXPECT_EQ(held.T_W_C.t, poses.back().t);
}

TEST(CameraTrajectory, WithoutVisionFollowsTheInsThroughTheMounting) {
  const InsBodyTrack ins = exactIns(0.0);
  const CameraTrajectory trajectory({}, {}, &ins, kT_B_C, 0.25);
  const TimedCameraPose at = trajectory.at(5.0);
  EXPECT_EQ(at.source, PoseSource::ins_only);
  EXPECT_TRUE(at.T_W_C.t.isApprox((trueBody(5.0) * kT_B_C).t, 1e-12));
  EXPECT_EQ(trajectory.at(-1.0).source, PoseSource::held);
  EXPECT_THROW(CameraTrajectory({}, {}, nullptr, kT_B_C, 0.25), std::invalid_argument);
}

}  // namespace
}  // namespace hsmap
