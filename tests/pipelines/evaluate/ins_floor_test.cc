// computeInsFloor on fixes built from a known trajectory: exact fixes give a
// floor of zero, fixes scaled about a point give that scale, and the fixes
// outside the frames' span are not used.
#include "pipelines/evaluate/ins_floor.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/so3.h"

namespace hsmap {
namespace {

// A curved, climbing path with attitude, sampled at 25 Hz for 4 s.
SE3d bodyPose(double t) {
  const Eigen::Vector3d p(100.0 + 0.6 * t, -50.0 + 0.8 * std::sin(0.7 * t), 30.0 + 0.1 * t);
  return SE3d(quaternionFromRollPitchHeadingDeg(3.0 * std::sin(t), 2.0 * std::cos(0.5 * t),
                                                40.0 + 10.0 * std::sin(0.4 * t)),
              p);
}

class InsFloorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ins_.T_B_C.rotation = Eigen::Quaterniond(0.5, 0.5, 0.5, 0.5);
    ins_.T_B_C.translation_m = Eigen::Vector3d(0.5, 0.0, 0.3);
    T_B_C_ = SE3d(ins_.T_B_C.rotation, ins_.T_B_C.translation_m);
    for (int i = 0; i <= 100; ++i) frames_.push_back({i * 0.04, bodyPose(i * 0.04) * T_B_C_});
  }

  // Fixes on the true body at every 4th frame time, plus two outside the
  // span; with `scale`, of the camera trajectory scaled about `about`.
  std::vector<InsFixInWorld> fixes(double scale, const Eigen::Vector3d& about, bool attitude) const {
    std::vector<InsFixInWorld> result;
    std::vector<double> times = {-0.5};
    for (int i = 0; i <= 100; i += 4) times.push_back(i * 0.04);
    times.push_back(4.5);
    for (double t : times) {
      const SE3d T_W_B = bodyPose(t);
      InsFixInWorld fix;
      fix.t = t;
      // The map (the camera trajectory) scaled about `about`, the body the
      // metric lever arm away from its camera: what an INS sees of a map
      // whose scale is off.
      const SE3d T_W_C = T_W_B * T_B_C_;
      fix.p_W_B = about + scale * (T_W_C.t - about) + (T_W_B.t - T_W_C.t);
      if (attitude) fix.q_W_B = T_W_B.q;
      result.push_back(fix);
    }
    return result;
  }

  InsConfig ins_;
  SE3d T_B_C_;
  std::vector<TimedPose> frames_;
};

TEST_F(InsFloorTest, FixesExactlyOnTheTruthGiveZero) {
  for (bool attitude : {true, false}) {
    const InsFloor floor = computeInsFloor(frames_, fixes(1.0, Eigen::Vector3d::Zero(), attitude), ins_);
    ASSERT_TRUE(floor.rgb_ate_m.value) << floor.rgb_ate_m.reason;
    EXPECT_NEAR(*floor.rgb_ate_m.value, 0.0, 1e-9);
    EXPECT_NEAR(*floor.scale_error.value, 0.0, 1e-10);
    EXPECT_EQ(floor.fixes_used, 26u);  // the fixes at -0.5 s and 4.5 s are outside the frames
  }
}

TEST_F(InsFloorTest, FixesScaledAboutAPointGiveThatScaleAndTheMovedFrames) {
  const Eigen::Vector3d about(101.0, -50.0, 30.0);
  for (bool attitude : {true, false}) {
    const InsFloor floor = computeInsFloor(frames_, fixes(1.01, about, attitude), ins_);
    ASSERT_TRUE(floor.scale_error.value) << floor.scale_error.reason;
    EXPECT_NEAR(*floor.scale_error.value, 0.01, 1e-9);
    // S p = about + 1.01 (p - about), so each camera centre moves by 0.01 (p - about).
    double sum = 0.0;
    for (const TimedPose& frame : frames_) sum += (0.01 * (frame.T.t - about)).squaredNorm();
    EXPECT_NEAR(*floor.rgb_ate_m.value, std::sqrt(sum / frames_.size()), 1e-9);
  }
}

TEST_F(InsFloorTest, TooFewFixesInTheFramesSpanLeaveTheFloorMissingWithTheReason) {
  std::vector<InsFixInWorld> two = fixes(1.0, Eigen::Vector3d::Zero(), false);
  two.erase(two.begin() + 3, two.end() - 1);  // -0.5, 0, 0.16 and 4.5 s
  const InsFloor floor = computeInsFloor(frames_, two, ins_);
  EXPECT_FALSE(floor.rgb_ate_m.value);
  EXPECT_FALSE(floor.scale_error.value);
  EXPECT_EQ(floor.rgb_ate_m.reason,
            "2 INS fix(es) within the frames' time span [0, 4] s; need 3 without attitude to fix "
            "a similarity");
}

}  // namespace
}  // namespace hsmap
