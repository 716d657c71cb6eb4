#include "pipelines/frontend/segment_linker.h"

#include <gtest/gtest.h>

#include <utility>

#include "tests/pipelines/frontend/synthetic_scene.h"

namespace hsmap {
namespace {

// A vehicle flying north at 0.4 m/s, 2 m above the seabed, with a lever arm
// to the camera, a camera looking down with the image top forward, and the
// INS at 1 Hz. Its camera poses at 5 Hz seen in a segment frame S that is a
// known similarity away from W.
struct Flight {
  std::vector<double> ins_times;
  std::vector<Eigen::Vector3d> p_W_B;
  std::vector<Eigen::Quaterniond> q_W_B;
  SE3d T_B_C;
  std::vector<double> times;
  std::vector<SE3d> T_W_C;
};

Flight fly(double t0, double t1) {
  Flight f;
  // Camera C: z down (W's z), x east... top of the image forward (north).
  f.T_B_C = SE3d(Eigen::Quaterniond(0.7071068, 0.0, 0.0, 0.7071068).normalized(), Eigen::Vector3d(0.5, 0.0, 0.3));
  auto body = [](double t) {
    const Eigen::Quaterniond q = quaternionFromRollPitchHeadingDeg(3.0 * std::sin(0.5 * t), 2.0 * std::cos(0.3 * t), 5.0 * std::sin(0.1 * t));
    return SE3d(q, Eigen::Vector3d(0.4 * t, 0.2 * std::sin(0.2 * t), 38.0 + 0.05 * std::sin(0.4 * t)));
  };
  for (double t = 0.0; t <= 40.0; t += 1.0) {
    const SE3d T = body(t);
    f.ins_times.push_back(t);
    f.p_W_B.push_back(T.t);
    f.q_W_B.push_back(T.q);
  }
  for (double t = t0; t <= t1; t += 0.2) {
    f.times.push_back(t);
    f.T_W_C.push_back(body(t) * f.T_B_C);
  }
  return f;
}

// The flight's INS as the linker's body track; without attitude the fixes
// carry none (identity).
InsBodyTrack insTrack(const Flight& f, bool has_attitude) {
  std::vector<InsBodyFix> fixes;
  for (std::size_t i = 0; i < f.ins_times.size(); ++i) {
    fixes.push_back({f.ins_times[i], f.p_W_B[i],
                     has_attitude ? f.q_W_B[i] : Eigen::Quaterniond::Identity(), 0});
  }
  return InsBodyTrack(std::move(fixes), has_attitude, kSegmentLinkerInsOptions);
}

TEST(SegmentLinker, RecoversTheSimilarityOfASegmentFromTheInsWithAttitude) {
  const Flight f = fly(5.0, 15.0);
  const Sim3 S_S_W(0.3, expSO3(Eigen::Vector3d(0.3, -1.0, 2.0)), Eigen::Vector3d(1.0, -2.0, 0.5));
  std::vector<SE3d> T_S_C;
  for (const SE3d& T : f.T_W_C) T_S_C.push_back(S_S_W.transformPose(T));
  const InsBodyTrack ins = insTrack(f, true);
  const SegmentFit fit = fitSegmentToIns(f.times, T_S_C, ins, f.T_B_C, 4);
  ASSERT_TRUE(fit.ok) << fit.failure;
  const Sim3 expected = S_S_W.inverse();
  EXPECT_NEAR(fit.S_W_S.scale(), expected.scale(), 2e-3 * expected.scale());
  EXPECT_LT(testing::rotationAngleDeg(fit.S_W_S.rotation(), expected.rotation()), 0.05);
  // Camera positions land where they are (linear interpolation of 1 Hz fixes
  // of a smooth path: millimetres).
  for (std::size_t i = 0; i < f.times.size(); ++i) {
    EXPECT_LT((fit.S_W_S.apply(T_S_C[i].t) - f.T_W_C[i].t).norm(), 0.01) << i;
  }
  EXPECT_LT(fit.rms_m, 0.01);
}

TEST(SegmentLinker, WithoutAttitudeTheLeverArmComesFromTheFit) {
  const Flight f = fly(5.0, 30.0);
  const Sim3 S_S_W(2.0, expSO3(Eigen::Vector3d(0.1, 0.2, -0.3)), Eigen::Vector3d(0.0, 1.0, 0.0));
  std::vector<SE3d> T_S_C;
  for (const SE3d& T : f.T_W_C) T_S_C.push_back(S_S_W.transformPose(T));
  const InsBodyTrack ins = insTrack(f, false);
  const SegmentFit fit = fitSegmentToIns(f.times, T_S_C, ins, f.T_B_C, 4);
  ASSERT_TRUE(fit.ok) << fit.failure;
  double worst = 0.0;
  for (std::size_t i = 0; i < f.times.size(); ++i) worst = std::max(worst, (fit.S_W_S.apply(T_S_C[i].t) - f.T_W_C[i].t).norm());
  // Ignoring the 0.58 m lever arm would leave errors of its size.
  EXPECT_LT(worst, 0.05);
}

TEST(SegmentLinker, RefusesASegmentTooShortToFit) {
  const Flight f = fly(5.0, 5.6);
  const InsBodyTrack ins = insTrack(f, true);
  const SegmentFit fit = fitSegmentToIns(f.times, f.T_W_C, ins, f.T_B_C, 4);
  EXPECT_FALSE(fit.ok);
  EXPECT_NE(fit.failure.find("fewer than 4"), std::string::npos) << fit.failure;
  const Flight g = fly(5.0, 6.5);
  const SegmentFit short_fit = fitSegmentToIns(g.times, g.T_W_C, ins, f.T_B_C, 4);
  EXPECT_FALSE(short_fit.ok);
  EXPECT_NE(short_fit.failure.find("two INS fix intervals"), std::string::npos) << short_fit.failure;
}

}  // namespace
}  // namespace hsmap
