// evaluateRun on hand-made results whose errors are known: every metric must
// come out as the test works it out independently.
#include "pipelines/evaluate/evaluate_run.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/geometry/sim3.h"
#include "core/geometry/so3.h"
#include "tests/pipelines/evaluate/evaluation_fixture.h"

namespace hsmap {
namespace {

using testing::EvaluationFixture;

double value(const MetricValue& metric) {
  EXPECT_TRUE(metric.value.has_value()) << metric.reason;
  return metric.value.value_or(NAN);
}

EvaluationMetrics evaluate(const EvaluationFixture& fixture) {
  return evaluateRun(loadEvaluationInputs(fixture.run(), fixture.truth()));
}

class EvaluateRunTest : public ::testing::Test {
 protected:
  EvaluationFixture fixture_;
};

TEST_F(EvaluateRunTest, ResultsEqualToTheTruthScoreZero) {
  fixture_.writeRunEqualToTruth();
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_EQ(metrics.variant, "sequential");
  EXPECT_EQ(value(metrics.rgb_ate_m), 0.0);
  EXPECT_NEAR(value(metrics.rgb_ate_aligned_m), 0.0, 1e-12);
  EXPECT_NEAR(value(metrics.rgb_scale_error), 0.0, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), 0.0, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_positions_aligned_m), 0.0, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_positions_aligned_deg), 0.0, 1e-9);
  // h: the cameras fly ~1.7 m above the flat seabed at down 22, tilted by
  // a few degrees at most.
  EXPECT_GT(value(metrics.alignment_view_distance_m), 1.6);
  EXPECT_LT(value(metrics.alignment_view_distance_m), 1.8);
  EXPECT_EQ(value(metrics.extrinsic_rotation_error_deg), 0.0);
  EXPECT_EQ(value(metrics.extrinsic_translation_error_m), 0.0);
  EXPECT_EQ(value(metrics.time_offset_error_s), 0.0);
  // The INS fixes lie on the true body: nothing to correct.
  EXPECT_NEAR(value(metrics.ins_floor_rgb_ate_m), 0.0, 1e-7);
  EXPECT_NEAR(value(metrics.ins_floor_scale_error), 0.0, 1e-8);
  // Not measurable yet, and saying why.
  for (const MetricValue* missing : {&metrics.mesh_accuracy_m, &metrics.mesh_completeness,
                                     &metrics.ortho_mean_shift_m, &metrics.ortho_coverage,
                                     &metrics.ortho_pixel_error_m, &metrics.ortho_pixel_error_abs_m}) {
    EXPECT_FALSE(missing->value.has_value());
    EXPECT_FALSE(missing->reason.empty());
  }
  using Timing = std::pair<std::string, double>;
  EXPECT_EQ(metrics.timings_s,
            (std::vector<Timing>{{"frontend", 12.5}, {"georef", 3.25}, {"total", 15.75}}));
  EXPECT_EQ(value(metrics.peak_rss_mb), 300.5);
}

TEST_F(EvaluateRunTest, ARigidShiftIsAllGeoReferencingError) {
  const Eigen::Vector3d shift(0.3, -0.4, 0.12);
  std::vector<TimedPose> frames = fixture_.framesTrue();
  for (TimedPose& pose : frames) pose.T.t += shift;
  std::vector<LinePose> lines = fixture_.linesTrue();
  for (LinePose& pose : lines) pose.T.t += shift;
  fixture_.writeRun(frames, lines, fixture_.calibrationEqualToTruth());
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.rgb_ate_m), shift.norm(), 1e-12);
  EXPECT_NEAR(value(metrics.rgb_ate_aligned_m), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.rgb_scale_error), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), 0.0, 1e-6);
}

TEST_F(EvaluateRunTest, ARotatedAndScaledTrajectoryHasItsScaleErrorAndAPerfectShape) {
  // The run's frame is the truth seen through S_est_true: 5 % larger, turned
  // 20 degrees, moved. The alignment maps it back with s = 1 / 1.05.
  const Sim3 S_est_true(1.05, Eigen::Quaterniond(Eigen::AngleAxisd(0.349, Eigen::Vector3d(1, 2, 3).normalized())),
                        Eigen::Vector3d(2.0, -1.0, 0.5));
  std::vector<TimedPose> frames = fixture_.framesTrue();
  double sum = 0.0;
  for (TimedPose& pose : frames) {
    const Eigen::Vector3d p_true = pose.T.t;
    pose.T = S_est_true.transformPose(pose.T);
    sum += (pose.T.t - p_true).squaredNorm();
  }
  std::vector<LinePose> lines = fixture_.linesTrue();
  for (LinePose& pose : lines) pose.T = S_est_true.transformPose(pose.T);
  fixture_.writeRun(frames, lines, fixture_.calibrationEqualToTruth());
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.rgb_ate_m), std::sqrt(sum / frames.size()), 1e-12);
  EXPECT_NEAR(value(metrics.rgb_scale_error), 1.0 - 1.0 / 1.05, 1e-9);
  EXPECT_NEAR(value(metrics.rgb_ate_aligned_m), 0.0, 1e-9);
  // Both alignments recover S_est_true^-1: the scan lines are exact.
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), 0.0, 1e-6);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_positions_aligned_m), 0.0, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_positions_aligned_deg), 0.0, 1e-6);
}

// The scan-line poses of a run that used this time offset and extrinsic:
// line k at its recorded time + d_est, T_W_U = T_W_B T_B_C T_C_U_est (what a
// wrong d or T_C_U does to a run).
std::vector<LinePose> linesWith(const EvaluationFixture& fixture, const RunCalibration& calibration) {
  const SE3d T_B_C(fixture.config().ins.T_B_C.rotation, fixture.config().ins.T_B_C.translation_m);
  const SE3d T_C_U(calibration.T_C_U.rotation, calibration.T_C_U.translation_m);
  std::vector<LinePose> lines;
  for (const LinePose& line : fixture.linesTrue()) {
    const double t = line.t - testing::kTrueTimeOffset + calibration.time_offset_s;
    lines.push_back({line.line, t, testing::trueBodyPose(t) * T_B_C * T_C_U});
  }
  return lines;
}

TEST_F(EvaluateRunTest, TimeOffsetAndExtrinsicErrorsAreThoseOfCalibrationYaml) {
  RunCalibration calibration = fixture_.calibrationEqualToTruth();
  calibration.time_offset_s += 0.004;
  // 1.5 degrees about an oblique axis, and 5 mm of translation.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(1.5 * so3_detail::kDegToRad,
                                                  Eigen::Vector3d(1, -1, 2).normalized()));
  calibration.T_C_U.rotation = calibration.T_C_U.rotation * turn;
  calibration.T_C_U.translation_m += Eigen::Vector3d(0.003, -0.004, 0.0);
  fixture_.writeRun(fixture_.framesTrue(), linesWith(fixture_, calibration), calibration);
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.time_offset_error_s), 0.004, 1e-15);
  EXPECT_NEAR(value(metrics.extrinsic_rotation_error_deg), 1.5, 1e-9);
  EXPECT_NEAR(value(metrics.extrinsic_translation_error_m), 0.005, 1e-15);
  // The frames are untouched.
  EXPECT_EQ(value(metrics.rgb_ate_m), 0.0);
}

TEST_F(EvaluateRunTest, AWrongExtrinsicTurnsAndMovesEveryScanLineByItsError) {
  RunCalibration calibration = fixture_.calibrationEqualToTruth();
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(1.5 * so3_detail::kDegToRad,
                                                  Eigen::Vector3d(1, -1, 2).normalized()));
  calibration.T_C_U.rotation = calibration.T_C_U.rotation * turn;
  calibration.T_C_U.translation_m += Eigen::Vector3d(0.003, -0.004, 0.0);
  fixture_.writeRun(fixture_.framesTrue(), linesWith(fixture_, calibration), calibration);
  const EvaluationMetrics metrics = evaluate(fixture_);
  // The frames are exact, so the view Sim(3) is the identity: every line is
  // turned by the extrinsic's 1.5 degrees and moved by its 5 mm (turned by
  // R_W_C, which keeps lengths).
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), 1.5, 1e-9);
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), 0.005, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_positions_aligned_deg), 1.5, 1e-9);
}

TEST_F(EvaluateRunTest, AWrongTimeOffsetMovesEveryScanLineAlongItsMotion) {
  // d 4 ms too large: every scan line is posed where the vehicle was 4 ms
  // after its true exposure.
  constexpr double kOffsetError = 0.004;
  RunCalibration calibration = fixture_.calibrationEqualToTruth();
  calibration.time_offset_s += kOffsetError;
  const std::vector<LinePose> lines = linesWith(fixture_, calibration);
  fixture_.writeRun(fixture_.framesTrue(), lines, calibration);
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.time_offset_error_s), kOffsetError, 1e-15);
  EXPECT_EQ(value(metrics.extrinsic_rotation_error_deg), 0.0);

  // With exact frames the view Sim(3) is the identity: the errors are the
  // lines' own motion over 4 ms.
  double position_sum = 0.0, angle_sum = 0.0;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const SE3d& T_true = fixture_.linesTrue()[k].T;
    position_sum += (lines[k].T.t - T_true.t).squaredNorm();
    const double angle = Eigen::AngleAxisd(T_true.q.conjugate() * lines[k].T.q).angle() / so3_detail::kDegToRad;
    angle_sum += angle * angle;
  }
  const double position_rmse = std::sqrt(position_sum / lines.size());
  const double rotation_rmse = std::sqrt(angle_sum / lines.size());
  EXPECT_NEAR(value(metrics.uhi_position_rmse_m), position_rmse, 1e-12);
  EXPECT_NEAR(value(metrics.uhi_rotation_rmse_deg), rotation_rmse, 1e-9);
  // The body moves at 0.5-0.62 m/s (north 0.5, east up to 0.36, down 0.05)
  // and turns at a few degrees per second: 2-2.5 mm and hundredths of a
  // degree, as a 4 ms error must give.
  EXPECT_GT(value(metrics.uhi_position_rmse_m), 0.0019);
  EXPECT_LT(value(metrics.uhi_position_rmse_m), 0.0027);
  EXPECT_GT(value(metrics.uhi_rotation_rmse_deg), 0.001);
  EXPECT_LT(value(metrics.uhi_rotation_rmse_deg), 0.03);
}

TEST_F(EvaluateRunTest, AStackedRunHasEveryMetricNullWithTheReason) {
  fixture_.writeRunEqualToTruth();
  RunRecord record = EvaluationFixture::record();
  record.variant = "stacked";
  record.survey = std::filesystem::absolute(fixture_.survey());
  writeRunRecord(fixture_.run() / "run.yaml", record);
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_EQ(metrics.variant, "stacked");
  for (const MetricRow& row : metricRows()) {
    const MetricValue& metric = metrics.*row.value;
    const std::string key = row.key;
    if (key == "peak_rss_mb") continue;
    EXPECT_FALSE(metric.value.has_value() && key.rfind("uhi_focal", 0) != 0 && key.rfind("uhi_cx", 0) != 0) << key;
    if (key.rfind("reflectance", 0) == 0 || key == "water_attenuation_rmse_per_m") {
      EXPECT_EQ(metric.reason, kStackedMakesNoReflectance) << key;
    } else if (key.rfind("rgb_focal", 0) == 0 || key == "rgb_cx_error_px" || key == "rgb_cy_error_px") {
      EXPECT_EQ(metric.reason, kStackedUsesNoRgbCamera) << key;
    } else if (key == "uhi_focal_error_rel" || key == "uhi_cx_error_px") {
      // The scan lines were laid side by side through survey.yaml's camera:
      // its error against the truth applies to stacked too.
      EXPECT_TRUE(metric.value.has_value()) << key;
    } else {
      EXPECT_EQ(metric.reason, kStackedHasNoPoses) << key;
    }
  }
  EXPECT_TRUE(metrics.uhi_distortion_error[0].value && metrics.uhi_distortion_error[1].value);
}

TEST_F(EvaluateRunTest, AnInsOnlyStyleTrajectoryScoresItsOwnPositionError) {
  // Truth plus the slow, smooth error of dead reckoning.
  const auto error = [](double t) {
    const double tau = t - testing::kStartTime;
    return Eigen::Vector3d(0.05 * std::sin(2.0 * tau), 0.03 * tau, -0.02 * std::cos(tau));
  };
  std::vector<TimedPose> frames = fixture_.framesTrue();
  double sum = 0.0;
  for (TimedPose& pose : frames) {
    pose.T.t += error(pose.t);
    sum += error(pose.t).squaredNorm();
  }
  std::vector<LinePose> lines = fixture_.linesTrue();
  for (LinePose& pose : lines) pose.T.t += error(pose.t);
  fixture_.writeRun(frames, lines, fixture_.calibrationEqualToTruth());
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.rgb_ate_m), std::sqrt(sum / frames.size()), 1e-12);
  // The error is not a similarity: some of it stays after the alignment.
  EXPECT_GT(value(metrics.rgb_ate_aligned_m), 1e-3);
  EXPECT_LT(value(metrics.rgb_ate_aligned_m), value(metrics.rgb_ate_m));
}

TEST_F(EvaluateRunTest, InsFixesScaledByOnePercentGiveAnInsFloorScaleErrorOfOnePercent) {
  fixture_.writeIns(1.01);
  fixture_.writeRunEqualToTruth();
  const EvaluationMetrics metrics = evaluate(fixture_);
  EXPECT_NEAR(value(metrics.ins_floor_scale_error), 0.01, 1e-8);
  // S = 1.01 about W's origin moves every camera centre by 0.01 p_W_C.
  double sum = 0.0;
  for (const TimedPose& pose : fixture_.framesTrue()) sum += (0.01 * pose.T.t).squaredNorm();
  EXPECT_NEAR(value(metrics.ins_floor_rgb_ate_m), std::sqrt(sum / fixture_.framesTrue().size()),
              1e-6);
  // The run itself is perfect: the floor is about the INS, not the run.
  EXPECT_EQ(value(metrics.rgb_ate_m), 0.0);
}

}  // namespace
}  // namespace hsmap
