// The joint problem on a reduced synthetic survey: a wobbly transect seen by
// a down-looking camera at 20 Hz (landmarks on a rippled seabed), INS fixes
// at 1 Hz on the spline, and push-broom tie points of a UHI whose extrinsic
// and time offset are unknown. From a start 2 deg / 5 cm / 15 ms off (the
// simulator's guess) and a trajectory a centimetre off, the solve must
// recover T_C_U and d within their stated 1-sigma (3 sigma) and those sigmas
// must be small enough to matter.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "core/geometry/pushbroom_camera.h"
#include "core/geometry/so3.h"
#include "pipelines/joint/joint_problem.h"
#include "pipelines/joint/joint_spline.h"
#include "tests/support/synthetic_transect.h"

namespace hsmap {
namespace {

constexpr double kDeg = M_PI / 180.0;

struct ReducedSurvey {
  test::Transect transect;
  FrontendResult frontend;
  VisualMap map;
  std::vector<double> frame_times;
  std::unique_ptr<InsBodyTrack> ins;
  PushbroomParameters uhi;
  SE3d T_C_U_truth;
  double d_truth = 0.015;
  std::vector<JointTiePoint> ties;
};

// `steady`: constant attitude and every tie point at the same range (a flat
// seabed flown level), the case that leaves T_C_U and d weakly observed.
constexpr std::size_t kKeyframeEvery = 4;

// `uhi_distortion`: the true UHI's [k1 k2]; `columns`: the samples every line
// ties (spread across the swath).
ReducedSurvey makeSurvey(unsigned seed, bool steady = false, std::array<double, 2> uhi_distortion = {0.0, 0.0},
                         std::vector<double> columns = {150.0, 560.0, 960.0, 1360.0, 1770.0}) {
  test::TransectConfig config;
  config.seed = seed;
  if (steady) config.dynamics = 0.0;
  config.num_keyframes = 161;  // 8 s of frames at 20 Hz
  config.keyframe_interval_s = 0.05;
  config.num_landmarks = 600;
  config.start_pose_sigma_m = 0.01;
  config.start_pose_sigma_deg = 0.1;
  config.start_landmark_sigma_m = 0.01;
  ReducedSurvey survey;
  survey.transect = test::makeTransect(config);
  const test::Transect& t = survey.transect;

  // Every 4th frame is a keyframe of the map. Its observations are the
  // map's; the front-end's per-frame list holds only those of even
  // landmarks, as it lacks a track's early life (the joint problem must take
  // a keyframe's observations from the map).
  for (const Eigen::Vector3d& p : t.start_p_W) survey.map.addLandmark(0, p);
  for (std::size_t k = 0; k < t.keyframe_times.size(); ++k) {
    FrameRecord record;
    record.index = int(k);
    record.t = t.keyframe_times[k];
    record.posed = true;
    if (k % kKeyframeEvery == 0) {
      record.keyframe = true;
      record.keyframe_id = survey.map.addKeyframe(int(k), record.t, 0, t.start_T_W_C[k]);
    }
    survey.frontend.frames.push_back(record);
    survey.frame_times.push_back(t.keyframe_times[k]);
  }
  for (const test::PixelObservation& o : t.observations) {
    const FrameRecord& frame = survey.frontend.frames[std::size_t(o.keyframe)];
    if (frame.keyframe) {
      survey.map.addObservation(frame.keyframe_id, o.landmark, o.pixel);
      if (o.landmark % 2 != 0) continue;
    }
    survey.frontend.frame_observations.push_back(
        {o.keyframe, o.landmark, float(o.pixel.x()), float(o.pixel.y())});
  }

  std::vector<InsBodyFix> fixes;
  for (std::size_t k = 0; k < t.keyframe_times.size(); k += 20) {
    fixes.push_back({t.keyframe_times[k], t.ins_p_W_B[k], t.ins_q_W_B[k], 0});
  }
  survey.ins = std::make_unique<InsBodyTrack>(std::move(fixes), true);

  survey.uhi.samples = 1920;
  survey.uhi.f = 1500.0;
  survey.uhi.cx = 960.0;
  survey.uhi.distortion = uhi_distortion;
  survey.T_C_U_truth = SE3d(expSO3(Eigen::Vector3d(0.3, -0.2, 0.5) * kDeg), Eigen::Vector3d(0.02, 0.1, 0.01));
  const PushbroomCamera uhi(survey.uhi);
  std::mt19937 rng(seed + 100);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double end = t.truth_spline.validEnd();
  for (long long line = 0;; ++line) {
    const double t_true = 0.3 + line / 30.0;
    if (t_true > end - 0.3) break;
    const SE3d T_W_U = t.truth_spline.pose(t_true) * survey.T_C_U_truth;
    for (double u : columns) {
      const Eigen::Vector3d ray = *uhi.unproject(u);
      const double range = steady ? 3.0 : 2.6 + 0.8 * uniform(rng);  // relief: ranges vary
      survey.ties.push_back({line, t_true - survey.d_truth, u + 0.3 * normal(rng), range,
                             T_W_U * (ray * range / ray.z())});
    }
  }
  return survey;
}

JointInputs inputsOf(const ReducedSurvey& survey) {
  const test::Transect& t = survey.transect;
  std::vector<TimedPose> frames;
  for (std::size_t k = 0; k < t.keyframe_times.size(); ++k) {
    frames.push_back({t.keyframe_times[k], t.start_T_W_C[k]});
  }
  JointInputs in;
  in.spline = splineThroughPoses(frames, chooseKnotSpacing(frames).dt_s);
  in.map_W = &survey.map;
  in.frontend = &survey.frontend;
  in.frame_times = &survey.frame_times;
  in.ins = survey.ins.get();
  in.T_B_C = t.T_B_C;
  in.ins_noise.sigma_horizontal_m = t.config.ins_sigma_horizontal_m;
  in.ins_noise.sigma_depth_m = t.config.ins_sigma_depth_m;
  in.ins_noise.sigma_attitude_rad =
      Eigen::Vector3d(t.config.ins_sigma_roll_pitch_deg, t.config.ins_sigma_roll_pitch_deg,
                      t.config.ins_sigma_heading_deg) * kDeg;
  in.tie_points = survey.ties;
  in.rgb_camera = t.camera;
  in.uhi_camera = survey.uhi;
  // The guess: 2 deg, 5 cm and 15 ms off.
  in.T_C_U_prior = survey.T_C_U_truth *
                   SE3d(expSO3(Eigen::Vector3d(1.2, -1.2, 1.0).normalized() * 2.0 * kDeg),
                        Eigen::Vector3d(0.03, -0.03, 0.028));
  in.sigma_rotation_deg = 2.0;
  in.sigma_translation_m = 0.05;
  in.time_offset_prior_s = 0.0;
  in.time_offset_sigma_s = 0.05;
  in.T_C_U_start = in.T_C_U_prior;
  in.time_offset_start_s = 0.0;
  return in;
}

JointOptions testOptions() {
  JointOptions options;
  options.pixel_sigma_px = 0.5;
  // The synthetic frames' pixels carry independent noise, not a track's
  // shared KLT drift, so the other frames count as much as the keyframes.
  options.other_frame_sigma_factor = 1.0;
  options.sigma_match_m = 0.3 / 1500.0 * 3.0;  // 0.3 px at 3 m
  options.num_threads = 2;
  return options;
}

// With the product's weighting of the frames between keyframes (the
// default other_frame_sigma_factor, as `hsmap run` solves it) and with the
// synthetic survey's own (its frames' pixels are as independent as the
// keyframes').
TEST(JointProblem, RecoversExtrinsicAndTimeOffsetWithinTheirStatedSigma) {
  for (const auto& [seed, factor] : {std::pair{1u, JointOptions{}.other_frame_sigma_factor}, std::pair{2u, 1.0},
                                     std::pair{1u, 1.0}, std::pair{2u, JointOptions{}.other_frame_sigma_factor}}) {
    SCOPED_TRACE("seed " + std::to_string(seed) + ", other_frame_sigma_factor " + std::to_string(factor));
    const ReducedSurvey survey = makeSurvey(seed);
    JointOptions options = testOptions();
    options.other_frame_sigma_factor = factor;
    const JointResult result = solveJointProblem(inputsOf(survey), options);
    ASSERT_TRUE(result.solved) << result.summary();
    ASSERT_TRUE(result.sigma_rotation_deg && result.sigma_translation_m && result.time_offset_sigma_s)
        << result.summary();

    const SE3d error = survey.T_C_U_truth.inverse() * result.T_C_U;
    const Eigen::Vector3d rotation_error_deg = logSO3(error.q) / kDeg;  // about U's axes
    const Eigen::Vector3d translation_error = result.T_C_U.t - survey.T_C_U_truth.t;  // in C
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(rotation_error_deg[i]), 3.0 * (*result.sigma_rotation_deg)[i]) << result.summary();
      EXPECT_LT(std::abs(translation_error[i]), 3.0 * (*result.sigma_translation_m)[i]) << result.summary();
    }
    EXPECT_LT(std::abs(result.time_offset_s - survey.d_truth), 3.0 * *result.time_offset_sigma_s)
        << result.summary();
    // The data, not the prior, determined them: sigmas far below the
    // prior's (2 deg, 5 cm). With the product's weighting the frames between
    // keyframes count a hundredth as much on this short transect, and the
    // translation's 1-sigma is held below a fifth of the prior's, 10 mm
    // (6.8-6.9 mm measured), rather than below 5 mm.
    const bool product_weighting = factor == JointOptions{}.other_frame_sigma_factor;
    EXPECT_LT(result.sigma_rotation_deg->maxCoeff(), 0.05);
    EXPECT_LT(result.sigma_translation_m->maxCoeff(), product_weighting ? 0.010 : 0.005);
    EXPECT_LT(*result.time_offset_sigma_s, 0.002);
    EXPECT_TRUE(result.weakly_determined.empty()) << result.summary();
    // The tie points' residuals on the ground are the noise they were given:
    // 0.3 px across the line (0.6 mm at the 2.6-3.4 m ranges); along it they
    // carry none, and only the solved trajectory's small errors show.
    EXPECT_GT(result.rms_tie_across_m, 0.0004) << result.summary();
    EXPECT_LT(result.rms_tie_across_m, 0.0009) << result.summary();
    EXPECT_LT(result.rms_tie_along_m, 0.5 * result.rms_tie_across_m) << result.summary();

    // The trajectory's shape came back too: its placement and scale are the
    // INS's (9 fixes of 5 cm, 0.1-0.5 deg), so compare after the best
    // similarity (Eigen::umeyama), as rgb_ate_aligned_m does.
    const std::vector<double>& times = survey.transect.keyframe_times;
    Eigen::Matrix3Xd estimated(3, times.size()), truth(3, times.size());
    for (std::size_t k = 0; k < times.size(); ++k) {
      estimated.col(Eigen::Index(k)) = result.spline.pose(times[k]).t;
      truth.col(Eigen::Index(k)) = survey.transect.T_W_C[k].t;
    }
    const Eigen::Matrix4d alignment = Eigen::umeyama(estimated, truth, true);
    const Eigen::Matrix3Xd aligned =
        (alignment.topLeftCorner<3, 3>() * estimated).colwise() + alignment.topRightCorner<3, 1>();
    const double rms = std::sqrt((aligned - truth).colwise().squaredNorm().mean());
    EXPECT_LT(rms, 0.002);
  }
}

// Self-calibration (issue 44): the UHI's f 1 % off, cx 3 px off and k1 0.02
// off, with survey.yaml's sigmas of 15 px, 3 px, 0.02 and 0.01. The tie
// points are carried by the true trajectory (as the joint stage carries them
// by the surface's), at 9 columns across the swath over varying relief.
TEST(JointProblem, RecoversPerturbedPushbroomIntrinsicsWithinTheirStatedSigma) {
  const ReducedSurvey survey = makeSurvey(
      4, false, {0.03, -0.01}, {40.0, 260.0, 500.0, 740.0, 960.0, 1180.0, 1420.0, 1660.0, 1880.0});
  JointInputs inputs = inputsOf(survey);
  inputs.surface_trajectory = &survey.transect.truth_spline;
  inputs.uhi_camera.f = survey.uhi.f * 1.01;
  inputs.uhi_camera.cx = survey.uhi.cx + 3.0;
  inputs.uhi_camera.distortion = {survey.uhi.distortion[0] + 0.02, survey.uhi.distortion[1]};
  inputs.uhi_intrinsics_sigma = {15.0, 3.0, 0.02, 0.01};
  const JointResult result = solveJointProblem(inputs, testOptions());
  ASSERT_TRUE(result.solved) << result.summary();
  ASSERT_TRUE(result.uhi_intrinsics && result.uhi_intrinsics_sigma) << result.summary();
  const std::array<double, 4> truth{survey.uhi.f, survey.uhi.cx, survey.uhi.distortion[0], survey.uhi.distortion[1]};
  const std::array<double, 4> prior{15.0, 3.0, 0.02, 0.01};
  for (int i = 0; i < 4; ++i) {
    const double error = (*result.uhi_intrinsics)[std::size_t(i)] - truth[std::size_t(i)];
    const double sigma = (*result.uhi_intrinsics_sigma)[std::size_t(i)];
    EXPECT_LT(std::abs(error), 3.0 * sigma) << "parameter " << i << "\n" << result.summary();
    // The tie points, not the prior, determined it.
    EXPECT_LT(sigma, 0.3 * prior[std::size_t(i)]) << "parameter " << i << "\n" << result.summary();
  }
  EXPECT_TRUE(result.inseparable_intrinsics.empty()) << result.summary();
  const Eigen::Vector3d rotation_error_deg = logSO3((survey.T_C_U_truth.inverse() * result.T_C_U).q) / kDeg;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(rotation_error_deg[i]), 3.0 * (*result.sigma_rotation_deg)[i]) << result.summary();
  }
  EXPECT_LT(std::abs(result.time_offset_s - survey.d_truth), 3.0 * *result.time_offset_sigma_s) << result.summary();
}

TEST(JointProblem, AHeldIntrinsicStaysAtSurveyYamlsValue) {
  const ReducedSurvey survey = makeSurvey(4, false, {0.0, 0.0}, {40.0, 500.0, 960.0, 1420.0, 1880.0});
  JointInputs inputs = inputsOf(survey);
  inputs.surface_trajectory = &survey.transect.truth_spline;
  inputs.uhi_camera.f = survey.uhi.f * 1.01;
  inputs.uhi_intrinsics_sigma = {15.0, 0.0, 0.0, 0.0};
  const JointResult result = solveJointProblem(inputs, testOptions());
  ASSERT_TRUE(result.solved && result.uhi_intrinsics && result.uhi_intrinsics_sigma) << result.summary();
  EXPECT_NEAR((*result.uhi_intrinsics)[0], survey.uhi.f, 3.0 * (*result.uhi_intrinsics_sigma)[0]);
  EXPECT_EQ((*result.uhi_intrinsics)[1], inputs.uhi_camera.cx);
  EXPECT_EQ((*result.uhi_intrinsics)[2], 0.0);
  EXPECT_EQ((*result.uhi_intrinsics_sigma)[1], 0.0);
}

TEST(JointProblem, ASteadyFlightOverAFlatSeabedCannotSeparateTheUhiCentreFromTheRotation) {
  const ReducedSurvey survey = makeSurvey(5, /*steady=*/true);
  JointInputs inputs = inputsOf(survey);
  inputs.surface_trajectory = &survey.transect.truth_spline;
  inputs.uhi_intrinsics_sigma = {15.0, 3.0, 0.0, 0.0};
  const JointResult result = solveJointProblem(inputs, testOptions());
  ASSERT_TRUE(result.solved) << result.summary();
  bool cx_named = false;
  for (const std::string& warning : result.inseparable_intrinsics) {
    cx_named = cx_named || warning.find("uhi_camera.cx cannot be separated") != std::string::npos;
  }
  EXPECT_TRUE(cx_named) << result.summary();
}

TEST(JointProblem, AKeyframesObservationsComeFromTheMapAndTheOtherFramesFromTheFrontEnd) {
  const ReducedSurvey survey = makeSurvey(3);
  JointOptions options = testOptions();
  options.start_gate_px = 1e9;  // count every observation
  options.max_iterations = 1;
  const JointResult result = solveJointProblem(inputsOf(survey), options);
  ASSERT_TRUE(result.solved) << result.summary();

  std::size_t keyframe_observations = 0;
  for (const Keyframe& keyframe : survey.map.keyframes()) keyframe_observations += keyframe.observations.size();
  std::size_t other_frame_observations = 0;
  for (const FrameObservation& o : survey.frontend.frame_observations) {
    if (!survey.frontend.frames[std::size_t(o.frame)].keyframe) ++other_frame_observations;
  }
  ASSERT_GT(keyframe_observations, 0u);
  // The keyframes' odd landmarks are only in the map: taken from the
  // front-end's list, the keyframes would give half as many.
  EXPECT_EQ(std::size_t(result.keyframe_reprojection_factors), keyframe_observations);
  EXPECT_EQ(std::size_t(result.reprojection_factors - result.keyframe_reprojection_factors),
            other_frame_observations);
  EXPECT_EQ(result.frames, int(survey.frontend.frames.size()));
}

TEST(JointProblem, ASteadyFlightOverAFlatSeabedIsReportedWeaklyDetermined) {
  const ReducedSurvey survey = makeSurvey(5, /*steady=*/true);
  const JointResult result = solveJointProblem(inputsOf(survey), testOptions());
  ASSERT_TRUE(result.solved) << result.summary();
  // At one range and a steady attitude, a translation of the UHI along track
  // (C's y points aft here) looks like a rotation about the line's axis and
  // like a time offset: the data cannot tell them apart.
  const auto& weak = result.weakly_determined;
  EXPECT_NE(std::find(weak.begin(), weak.end(), "T_C_U translation along C's y"), weak.end())
      << result.summary();
}

TEST(JointProblem, TooFewTiePointsLeavesTheStartInPlaceWithAWarning) {
  const ReducedSurvey survey = makeSurvey(3);
  JointInputs inputs = inputsOf(survey);
  inputs.tie_points.resize(5);
  const JointResult result = solveJointProblem(inputs, testOptions());
  EXPECT_FALSE(result.solved);
  EXPECT_TRUE(result.T_C_U.q.isApprox(inputs.T_C_U_start.q));
  EXPECT_EQ(result.time_offset_s, inputs.time_offset_start_s);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_EQ(result.warnings[0],
            "only 5 usable cross-modal tie points (need 20): the joint problem is not solved");
}

TEST(JointProblem, TheSplinePastTheLastPosedFrameIsHeldByTheSmoothnessNotByAnInsFix) {
  // The spline's last segment reaches past the last posed frame (the knots
  // need not divide the frames' span): its last control point moves the
  // poses there by at most u^3/6 of itself, so the frames hardly hold it,
  // and an INS fix there (1 Hz, decimetres of noise) took it, and the scan
  // lines posed there, wherever its error pointed. With the smoothness
  // prior on the accelerations tying it to its neighbours, the fix weighs
  // as that prior and its own sigma say: solved with the fix 2 sigma off and
  // with it exact, the spline at the fix moves by a fraction of the offset.
  const ReducedSurvey survey = makeSurvey(6);
  JointInputs inputs = inputsOf(survey);
  const test::Transect& t = survey.transect;
  // A spline through the first 7.5 s of frames, knots every 0.35 s: valid
  // to 7.7 s (the truth is known to 8 s).
  std::vector<TimedPose> frames;
  for (std::size_t k = 0; k < t.keyframe_times.size() && t.keyframe_times[k] <= 7.5; ++k) {
    frames.push_back({t.keyframe_times[k], t.start_T_W_C[k]});
  }
  const double dt = 0.35;
  inputs.spline = splineThroughPoses(frames, dt);
  const double end = inputs.spline.validEnd();
  ASSERT_GT(end - frames.back().t, 0.1);  // a segment partly past the frames
  ASSERT_LT(end, t.truth_spline.validEnd());
  // The frames of the last segment's first 0.13 s are posed (three, at
  // u < 0.4: together less than 1 % of a frame's weight on the last
  // control point), and the tie points up to them (their prediction is
  // made from the frames); an INS fix near the segment's end.
  FrontendResult frontend = survey.frontend;
  const double last_posed = end - dt + 0.13;
  for (FrameRecord& frame : frontend.frames) frame.posed = frame.t <= last_posed;
  inputs.frontend = &frontend;
  inputs.tie_points.clear();
  for (const JointTiePoint& tie : survey.ties) {
    if (tie.t_recorded + inputs.time_offset_start_s <= last_posed) inputs.tie_points.push_back(tie);
  }
  const double t_fix = end - 0.01;
  const SE3d T_W_B_fix = t.truth_spline.pose(t_fix) * t.T_B_C.inverse();
  // 2 sigma of the reduced survey's 5 cm fixes.
  const Eigen::Vector3d offset = Eigen::Vector3d(0.06, -0.05, 0.05);
  auto solveWithLastFixOff = [&](const Eigen::Vector3d& fix_error, const JointOptions& options) {
    std::vector<InsBodyFix> fixes;
    for (const InsBodyFix& fix : survey.ins->fixes()) {
      if (fix.t < t_fix) fixes.push_back(fix);
    }
    fixes.push_back({t_fix, T_W_B_fix.t + fix_error, T_W_B_fix.q, 0});
    const InsBodyTrack ins(std::move(fixes), true);
    inputs.ins = &ins;
    return solveJointProblem(inputs, options);
  };
  // How far the fix's offset moves the spline, as a fraction of it, at
  // each of `times` (one pair of solves for all of them).
  auto pulledAt = [&](const std::vector<double>& times, const JointOptions& options) {
    const JointResult exact = solveWithLastFixOff(Eigen::Vector3d::Zero(), options);
    const JointResult off = solveWithLastFixOff(offset, options);
    EXPECT_TRUE(exact.solved && off.solved) << off.summary();
    std::vector<double> pulled;
    for (const double at : times) {
      pulled.push_back((off.spline.pose(at).t - exact.spline.pose(at).t).norm() / offset.norm());
    }
    return pulled;
  };
  // With the prior there, the fix weighs at most as the acceleration prior
  // alone lets it: 0.5 m/s^2 over the 0.2 s past the last frame allow 1 cm
  // (0.5 a t^2), against the fix's 5 cm: (1^2 / (1^2 + 5^2)) ~ 0.04 of its
  // offset, about twice that with the frames' own uncertainty at their end;
  // this survey: 0.09. The frames' count alone leaves the last control
  // point free (its support holds three frames): 0.39.
  JointOptions count_only = testOptions();
  count_only.min_frame_weight_in_support = 0.0;
  EXPECT_GT(pulledAt({t_fix}, count_only)[0], 0.3);
  const std::vector<double> pulled = pulledAt({t_fix, last_posed}, testOptions());
  EXPECT_LT(pulled[0], 0.15);
  // Up to the last posed frame the frames hold it.
  EXPECT_LT(pulled[1], 0.03);
}

// The reduced survey's inputs with d's start (and prior) 150 ms off, its
// prior sigma 200 ms.
JointInputs inputsStarting150msOff(const ReducedSurvey& survey) {
  JointInputs inputs = inputsOf(survey);
  inputs.time_offset_start_s = survey.d_truth - 0.15;
  inputs.time_offset_prior_s = inputs.time_offset_start_s;
  inputs.time_offset_sigma_s = 0.2;
  return inputs;
}

TEST(JointProblem, TimeOffsetStaysInsideTheFactorsWindow) {
  // A start 150 ms off: the tie factors' window covers +-0.45 knot
  // intervals (at most 90 ms here), so d is bounded there and, without
  // building the problem again around the new d, the result asks for
  // another round instead of extrapolating the spline.
  const ReducedSurvey survey = makeSurvey(4);
  const JointInputs inputs = inputsStarting150msOff(survey);
  JointOptions one_window = testOptions();
  one_window.max_rewindows = 0;
  const JointResult result = solveJointProblem(inputs, one_window);
  ASSERT_TRUE(result.solved) << result.summary();
  EXPECT_EQ(result.rewindows, 0);
  const double reach = 0.45 * inputs.spline.dt();
  ASSERT_LT(reach, 0.15);
  EXPECT_LE(std::abs(result.time_offset_s - inputs.time_offset_start_s), reach + 1e-9);
  bool asks_for_round = false;
  for (const std::string& warning : result.warnings) {
    asks_for_round |= warning.find("another round is needed") != std::string::npos;
  }
  EXPECT_TRUE(asks_for_round) << result.summary();
}

TEST(JointProblem, ATimeOffsetBeyondTheWindowIsReachedByBuildingTheProblemAgainAroundIt) {
  // The same start 150 ms off: built again around each bound d reaches,
  // the solve recovers d within its stated noise in one call.
  const ReducedSurvey survey = makeSurvey(4);
  const JointInputs inputs = inputsStarting150msOff(survey);
  const JointResult result = solveJointProblem(inputs, testOptions());
  ASSERT_TRUE(result.solved) << result.summary();
  EXPECT_GE(result.rewindows, 1);
  ASSERT_TRUE(result.time_offset_sigma_s.has_value()) << result.summary();
  EXPECT_LT(std::abs(result.time_offset_s - survey.d_truth), 3.0 * *result.time_offset_sigma_s)
      << result.summary();
  for (const std::string& warning : result.warnings) {
    EXPECT_EQ(warning.find("another round is needed"), std::string::npos) << warning;
  }
  EXPECT_NE(result.summary().find("built again around it"), std::string::npos);
}

TEST(JointSpline, KnotSpacingFollowsTheVehiclesMotion) {
  test::TransectConfig calm, lively;
  calm.dynamics = 0.1;
  lively.dynamics = 4.0;
  auto framesOf = [](const test::TransectConfig& config) {
    const SE3d T_B_C = test::cameraOnBody();
    std::vector<TimedPose> frames;
    for (int k = 0; k <= 250; ++k) frames.push_back({k * 0.04, test::vehicleMotion(config, k * 0.04) * T_B_C});
    return frames;
  };
  const KnotSpacingChoice calm_choice = chooseKnotSpacing(framesOf(calm));
  const KnotSpacingChoice lively_choice = chooseKnotSpacing(framesOf(lively));
  EXPECT_TRUE(calm_choice.within_tolerance) << calm_choice.reason;
  EXPECT_LT(lively_choice.dt_s, calm_choice.dt_s) << lively_choice.reason;
  EXPECT_GE(lively_choice.dt_s, 0.08);  // never below two frame intervals
}

TEST(JointSpline, SplineThroughPosesCoversTheFramesAndRejectsBadInput) {
  const SE3d T_B_C = test::cameraOnBody();
  std::vector<TimedPose> frames;
  for (int k = 0; k <= 25; ++k) frames.push_back({1.0 + k * 0.04, test::vehicleMotion({}, k * 0.04) * T_B_C});
  const SE3Splined spline = splineThroughPoses(frames, 0.2);
  EXPECT_DOUBLE_EQ(spline.validBegin(), 1.0);
  EXPECT_GE(spline.validEnd(), 2.0);
  EXPECT_THROW(splineThroughPoses({frames[0]}, 0.2), std::invalid_argument);
  EXPECT_THROW(splineThroughPoses(frames, 0.0), std::invalid_argument);
}

// A round's report: how far the trajectory moved. Control points moved by
// 1 mm along x move every pose by 1 mm; rotated by 0.1 deg about the
// camera's axis, every pose by 0.1 deg.
TEST(JointSpline, SplineChangeMeasuresHowFarARoundMovedTheTrajectory) {
  const SE3d T_B_C = test::cameraOnBody();
  std::vector<TimedPose> frames;
  std::vector<double> times;
  for (int k = 0; k <= 50; ++k) {
    frames.push_back({k * 0.04, test::vehicleMotion({}, k * 0.04) * T_B_C});
    times.push_back(k * 0.04);
  }
  times.push_back(-5.0);  // outside both splines: left out
  const SE3Splined before = splineThroughPoses(frames, 0.2);
  const auto [same_m, same_deg] = splineChange(before, before, times);
  EXPECT_NEAR(same_m, 0.0, 1e-12);
  EXPECT_NEAR(same_deg, 0.0, 1e-9);

  std::vector<SE3d> shifted, turned;
  const SE3d turn(expSO3(Eigen::Vector3d(0.0, 0.0, 0.1 * std::numbers::pi / 180.0)),
                  Eigen::Vector3d::Zero());
  for (const SE3d& T : before.controlPoints()) {
    shifted.push_back(SE3d(T.q, T.t + Eigen::Vector3d(0.001, 0.0, 0.0)));
    turned.push_back(T * turn);
  }
  const auto [shift_m, shift_deg] =
      splineChange(before, SE3Splined(before.t0(), before.dt(), shifted), times);
  EXPECT_NEAR(shift_m, 0.001, 1e-9);
  EXPECT_NEAR(shift_deg, 0.0, 1e-6);
  const auto [turn_m, turn_deg] =
      splineChange(before, SE3Splined(before.t0(), before.dt(), turned), times);
  EXPECT_NEAR(turn_m, 0.0, 1e-9);
  EXPECT_NEAR(turn_deg, 0.1, 1e-6);
}

}  // namespace
}  // namespace hsmap
