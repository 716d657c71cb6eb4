// interpolatePose and TimedPoseTrajectory: exact ends, the SO(3) geodesic,
// constant-velocity motion reproduced, no extrapolation, strict times.

#include "core/geometry/pose_interpolation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

SE3d poseA() {
  return SE3d(expSO3(Eigen::Vector3d(0.1, -0.4, 0.9)), Eigen::Vector3d(1.0, 2.0, 3.0));
}
SE3d poseB() {
  return SE3d(expSO3(Eigen::Vector3d(-0.7, 0.2, 1.6)), Eigen::Vector3d(-2.0, 0.5, 7.0));
}

double poseDistance(const SE3d& a, const SE3d& b) {
  return (a.t - b.t).norm() + a.q.angularDistance(b.q);
}

// Constant linear velocity v and constant angular velocity w (body frame):
// T(t) = (q0 exp(w t), p0 + v t), the motion the interpolation assumes.
SE3d constantVelocityPose(double t) {
  const Eigen::Quaterniond q0 = expSO3(Eigen::Vector3d(0.3, 0.1, -0.2));
  const Eigen::Vector3d w(0.05, -0.1, 0.4);  // rad/s
  const Eigen::Vector3d p0(10.0, -3.0, 17.0);
  const Eigen::Vector3d v(0.5, 0.1, -0.05);  // m/s
  return SE3d(q0 * expSO3(Eigen::Vector3d(w * t)), p0 + v * t);
}

std::string trajectoryError(std::vector<double> times, std::vector<SE3d> poses) {
  try {
    TimedPoseTrajectory trajectory(std::move(times), std::move(poses));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(PoseInterpolation, EndpointsAreExact) {
  const SE3d a = poseA(), b = poseB();
  const SE3d at0 = interpolatePose(a, b, 0.0);
  const SE3d at1 = interpolatePose(a, b, 1.0);
  EXPECT_EQ(at0.q.coeffs(), a.q.coeffs());
  EXPECT_EQ(at0.t, a.t);
  EXPECT_EQ(at1.q.coeffs(), b.q.coeffs());
  EXPECT_EQ(at1.t, b.t);
  // Just inside, the geodesic is continuous with its ends.
  EXPECT_LT(poseDistance(interpolatePose(a, b, 1e-12), a), 1e-11);
  EXPECT_LT(poseDistance(interpolatePose(a, b, 1.0 - 1e-12), b), 1e-11);
}

TEST(PoseInterpolation, MidpointOfARotationAboutAnAxisIsTheHalfAngleRotation) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -0.5).normalized();
  const double angle = 2.4;  // radians: large, where a linear blend of matrices would fail
  const SE3d a(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  const SE3d b(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), Eigen::Vector3d::Zero());
  const SE3d mid = interpolatePose(a, b, 0.5);
  const Eigen::Quaterniond half(Eigen::AngleAxisd(angle / 2.0, axis));
  EXPECT_LT(mid.q.angularDistance(half), 1e-14);
  EXPECT_EQ(mid.t, Eigen::Vector3d::Zero());
  // A quarter of the way: a quarter of the angle (constant angular rate).
  EXPECT_LT(interpolatePose(a, b, 0.25).q.angularDistance(
                Eigen::Quaterniond(Eigen::AngleAxisd(angle / 4.0, axis))),
            1e-14);
  // -q is the same rotation: the shorter arc is taken either way.
  const SE3d b_flipped(Eigen::Quaterniond(-b.q.coeffs()), b.t);
  EXPECT_LT(interpolatePose(a, b_flipped, 0.5).q.angularDistance(half), 1e-14);
}

TEST(PoseInterpolation, TranslationIsLinearNotAScrew) {
  // Turning by 90 degrees while moving 1 m along x: the centre stays on the
  // straight segment (a screw interpolation would bow it sideways).
  const SE3d a(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  const SE3d b(expSO3(Eigen::Vector3d(0.0, 0.0, M_PI / 2.0)), Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_LT((interpolatePose(a, b, 0.5).t - Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), 1e-15);
  EXPECT_GT((SE3d::interpolate(a, b, 0.5).t - Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), 0.1);
}

TEST(PoseInterpolation, AlphaOutsideTheUnitIntervalThrows) {
  EXPECT_THROW(interpolatePose(poseA(), poseB(), -1e-9), std::invalid_argument);
  EXPECT_THROW(interpolatePose(poseA(), poseB(), 1.5), std::invalid_argument);
  EXPECT_THROW(interpolatePose(poseA(), poseB(), NAN), std::invalid_argument);
}

TEST(TimedPoseTrajectory, ReproducesConstantVelocityMotion) {
  // Samples 0.7 s apart, unevenly: every time in between matches the motion.
  const std::vector<double> times = {100.0, 100.7, 101.4, 101.9, 103.0};
  std::vector<SE3d> poses;
  for (const double t : times) poses.push_back(constantVelocityPose(t - 100.0));
  const TimedPoseTrajectory trajectory(times, poses);
  for (double t = 100.0; t <= 103.0; t += 0.0625) {
    EXPECT_LT(poseDistance(trajectory.at(t), constantVelocityPose(t - 100.0)), 1e-12) << t;
  }
}

TEST(TimedPoseTrajectory, SampleTimesReturnTheSamplesExactly) {
  const std::vector<double> times = {0.0, 0.5, 1.0};
  const std::vector<SE3d> poses = {poseA(), poseB(), poseA()};
  const TimedPoseTrajectory trajectory(times, poses);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const SE3d pose = trajectory.at(times[k]);
    EXPECT_EQ(pose.q.coeffs(), poses[k].q.coeffs()) << k;
    EXPECT_EQ(pose.t, poses[k].t) << k;
  }
  EXPECT_EQ(trajectory.startTime(), 0.0);
  EXPECT_EQ(trajectory.endTime(), 1.0);
  EXPECT_EQ(trajectory.size(), 3u);
}

TEST(TimedPoseTrajectory, OutsideTheSpanThrowsInsteadOfExtrapolating) {
  const TimedPoseTrajectory trajectory({10.0, 11.0, 12.5}, {poseA(), poseB(), poseA()});
  EXPECT_TRUE(trajectory.covers(10.0));
  EXPECT_TRUE(trajectory.covers(12.5));
  EXPECT_FALSE(trajectory.covers(9.999));
  EXPECT_FALSE(trajectory.covers(12.5001));
  EXPECT_FALSE(trajectory.covers(NAN));
  try {
    trajectory.at(13.25);
    FAIL() << "expected std::out_of_range";
  } catch (const std::out_of_range& e) {
    EXPECT_STREQ(e.what(),
                 "TimedPoseTrajectory: t = 13.25 s is outside the trajectory's span [10, 12.5] s "
                 "(no extrapolation)");
  }
  EXPECT_THROW(trajectory.at(9.0), std::out_of_range);
  EXPECT_THROW(trajectory.at(NAN), std::out_of_range);
  // One sample covers only its own time.
  const TimedPoseTrajectory single({4.0}, {poseB()});
  EXPECT_EQ(single.at(4.0).t, poseB().t);
  EXPECT_THROW(single.at(4.0 + 1e-9), std::out_of_range);
}

TEST(TimedPoseTrajectory, RejectsTimesThatDoNotIncreaseStrictly) {
  EXPECT_EQ(trajectoryError({0.0, 1.0, 1.0}, {poseA(), poseB(), poseA()}),
            "TimedPoseTrajectory: times must increase strictly, but time 2 (1 s) follows 1 s");
  EXPECT_EQ(trajectoryError({0.0, 2.0, 1.5}, {poseA(), poseB(), poseA()}),
            "TimedPoseTrajectory: times must increase strictly, but time 2 (1.5 s) follows 2 s");
  EXPECT_EQ(trajectoryError({0.0, NAN}, {poseA(), poseB()}),
            "TimedPoseTrajectory: time 1 is not finite (nan)");
  EXPECT_EQ(trajectoryError({0.0, 1.0}, {poseA()}), 
            "TimedPoseTrajectory: times and poses must pair up, got 2 times and 1 poses");
  EXPECT_EQ(trajectoryError({}, {}), "TimedPoseTrajectory: no samples");
}

}  // namespace
}  // namespace hsmap
