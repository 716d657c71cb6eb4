#include "core/survey/ins_body_track.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// Fixes at 1 Hz along a straight track heading `heading_rad` at 0.4 m/s,
// with white position noise of `noise_m` per axis.
std::vector<InsBodyFix> straightTrack(double heading_rad, double noise_m, int count) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<InsBodyFix> fixes;
  for (int i = 0; i < count; ++i) {
    InsBodyFix fix;
    fix.t = 100.0 + i;
    fix.p_W_B = Eigen::Vector3d(0.4 * i * std::cos(heading_rad), 0.4 * i * std::sin(heading_rad), 10.0) +
                Eigen::Vector3d(noise(rng), noise(rng), 0.0);
    fix.line_number = i + 2;
    fixes.push_back(fix);
  }
  return fixes;
}

double yawDeg(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  return std::atan2(x.y(), x.x()) * 180.0 / M_PI;
}

TEST(InsBodyTrack, WithoutAttitudeTheBodyIsLevelAndHeadsAlongTheTrackDespiteFixNoise) {
  const double heading = 30.0 * M_PI / 180.0;
  const double sigma = 0.3, speed = 0.4, window_s = 20.0;
  const InsBodyTrack track(straightTrack(heading, sigma, 60), /*has_attitude=*/false, window_s);
  EXPECT_FALSE(track.hasAttitude());
  // A heading from two consecutive fixes would swing by ~45 degrees here.
  // The window's slope has a cross-track error of sigma / sqrt(sum dt^2),
  // i.e. 1.6 degrees for the 21 fixes of a full window; 4 sigma is allowed
  // (twice that where the window is cut by the track's ends).
  for (const auto& fix : track.fixes()) {
    const double dt_begin = fix.t - track.startTime(), dt_end = track.endTime() - fix.t;
    const int half = int(window_s / 2);
    double sum_dt2 = 0.0;
    const int first = -std::min(half, int(dt_begin)), last = std::min(half, int(dt_end));
    double mean = 0.0;
    for (int k = first; k <= last; ++k) mean += double(k) / double(last - first + 1);
    for (int k = first; k <= last; ++k) sum_dt2 += (k - mean) * (k - mean);
    const double sigma_deg = sigma / std::sqrt(sum_dt2) / speed * 180.0 / M_PI;
    EXPECT_NEAR(yawDeg(fix.q_W_B), 30.0, 4.0 * sigma_deg) << "at t = " << fix.t;
    const Eigen::Vector3d z = fix.q_W_B * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(z.z(), 1.0, 1e-12);  // level: the body's down is W's down
  }
}

TEST(InsBodyTrack, InterpolatesBetweenFixesAndNeverExtrapolates) {
  std::vector<InsBodyFix> fixes(2);
  fixes[0].t = 10.0;
  fixes[0].p_W_B = Eigen::Vector3d(0, 0, 5);
  fixes[0].q_W_B = Eigen::Quaterniond(Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ()));
  fixes[1].t = 11.0;
  fixes[1].p_W_B = Eigen::Vector3d(1, 2, 5);
  fixes[1].q_W_B = Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()));
  const InsBodyTrack track(fixes, /*has_attitude=*/true);
  const SE3d T = track.bodyPose(10.25);
  EXPECT_TRUE(T.t.isApprox(Eigen::Vector3d(0.25, 0.5, 5), 1e-12));
  EXPECT_NEAR(logSO3(T.q).z(), 0.05, 1e-12);
  EXPECT_TRUE(track.bodyPose(11.0).t.isApprox(fixes[1].p_W_B));
  EXPECT_FALSE(track.covers(11.01));
  EXPECT_THROW(track.bodyPose(11.01), std::out_of_range);
  EXPECT_THROW(track.bodyPose(9.99), std::out_of_range);
}

TEST(InsBodyTrack, RefusesFixesOutOfOrder) {
  auto fixes = straightTrack(0.0, 0.0, 3);
  fixes[2].t = fixes[1].t;
  try {
    InsBodyTrack track(fixes, false);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "InsBodyTrack: fix 2 at t = 101 s does not follow the previous one (t = 101 s)");
  }
}

TEST(InsBodyTrack, SlerpAndGeodesicAgreeBetweenFixesAndTheSlerpIsEigens) {
  std::vector<InsBodyFix> fixes(3);
  for (int i = 0; i < 3; ++i) {
    fixes[i].t = 10.0 + i;
    fixes[i].p_W_B = Eigen::Vector3d(0.4 * i, -0.1 * i * i, 5.0);
    fixes[i].q_W_B = quaternionFromRollPitchHeadingDeg(2.0 * i, -1.0 * i, 30.0 + 7.0 * i);
  }
  InsBodyTrackOptions options;
  options.attitude_interpolation = InsAttitudeInterpolation::quaternion_slerp;
  const InsBodyTrack slerp(fixes, /*has_attitude=*/true, options);
  const InsBodyTrack geodesic(fixes, /*has_attitude=*/true);
  for (const double t : {10.0, 10.3, 11.0, 11.7, 12.0}) {
    const SE3d a = slerp.bodyPose(t), b = geodesic.bodyPose(t);
    EXPECT_LT((a.t - b.t).norm(), 1e-12) << "at t = " << t;
    EXPECT_LT(std::abs(std::abs(a.q.dot(b.q)) - 1.0), 1e-12) << "at t = " << t;
  }
  // Slerp mode is Eigen's slerp, the last fix the end of the last interval.
  EXPECT_TRUE(slerp.bodyPose(11.7).q.coeffs() ==
              fixes[1].q_W_B.slerp((11.7 - 11.0) / (12.0 - 11.0), fixes[2].q_W_B).coeffs());
  EXPECT_TRUE(slerp.bodyPose(12.0).q.coeffs() == fixes[1].q_W_B.slerp(1.0, fixes[2].q_W_B).coeffs());
  EXPECT_THROW(slerp.bodyPose(12.01), std::out_of_range);
}

TEST(InsBodyTrack, WithoutAttitudeAndNoDerivationTheAttitudeStaysIdentity) {
  InsBodyTrackOptions options;
  options.derive_attitude = false;
  const InsBodyTrack track(straightTrack(0.5, 0.0, 10), /*has_attitude=*/false, options);
  EXPECT_FALSE(track.hasAttitude());
  for (const InsBodyFix& fix : track.fixes()) {
    EXPECT_TRUE(fix.q_W_B.coeffs() == Eigen::Quaterniond::Identity().coeffs()) << fix.t;
  }
}

TEST(InsBodyTrack, FixIntervalIsTheMedianGapBetweenFixes) {
  auto fixes = straightTrack(0.0, 0.0, 6);
  fixes[5].t = 200.0;  // one long gap does not move the median
  EXPECT_DOUBLE_EQ(InsBodyTrack(fixes, true).fixInterval(), 1.0);
  EXPECT_DOUBLE_EQ(InsBodyTrack(straightTrack(0.0, 0.0, 1), true).fixInterval(), 0.0);
}

}  // namespace
}  // namespace hsmap
