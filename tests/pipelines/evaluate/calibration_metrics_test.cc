// The calibration metrics: the extrinsic and time offset against the truth,
// and the UHI intrinsics the run used (calibration.yaml's uhi_camera when it
// estimated them, survey.yaml's otherwise).
#include "pipelines/evaluate/calibration_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hsmap {
namespace {

PushbroomParameters camera(double f, double cx, double k1, double k2) {
  PushbroomParameters p;
  p.samples = 1920;
  p.f = f;
  p.cx = cx;
  p.distortion = {k1, k2};
  return p;
}

TruthCalibration truth() {
  TruthCalibration t;
  t.T_C_U.translation_m = Eigen::Vector3d(0.1, 0.0, 0.0);
  t.time_offset_s = 0.015;
  t.uhi_camera = camera(1500.0, 959.5, 0.01, -0.002);
  return t;
}

TEST(CalibrationMetrics, TheSurveysCameraIsScoredWhenTheRunDidNotEstimateIt) {
  RunCalibration run;
  run.T_C_U.translation_m = Eigen::Vector3d(0.1, 0.003, -0.004);
  run.time_offset_s = 0.012;
  const CalibrationErrors errors = compareCalibration(run, camera(1515.0, 962.5, 0.03, -0.002), truth());
  EXPECT_NEAR(errors.extrinsic_translation_error_m, 0.005, 1e-12);
  EXPECT_NEAR(errors.extrinsic_rotation_error_deg, 0.0, 1e-9);
  EXPECT_NEAR(errors.time_offset_error_s, 0.003, 1e-12);
  EXPECT_NEAR(errors.uhi_focal_error_rel, 0.01, 1e-12);
  EXPECT_NEAR(errors.uhi_cx_error_px, 3.0, 1e-12);
  EXPECT_NEAR(errors.uhi_distortion_error[0], 0.02, 1e-12);
  EXPECT_NEAR(errors.uhi_distortion_error[1], 0.0, 1e-12);
}

TEST(CalibrationMetrics, TheRunsEstimateOfTheIntrinsicsIsScoredWhenItHasOne) {
  RunCalibration run;
  run.T_C_U.translation_m = Eigen::Vector3d(0.1, 0.0, 0.0);
  run.time_offset_s = 0.015;
  UhiCameraEstimate estimate;
  estimate.f = 1501.5;
  estimate.cx = 959.2;
  estimate.distortion = {0.0105, -0.0021};
  run.uhi_camera = estimate;
  const CalibrationErrors errors = compareCalibration(run, camera(1515.0, 962.5, 0.03, -0.002), truth());
  EXPECT_NEAR(errors.uhi_focal_error_rel, 0.001, 1e-12);
  EXPECT_NEAR(errors.uhi_cx_error_px, 0.3, 1e-9);
  EXPECT_NEAR(errors.uhi_distortion_error[0], 0.0005, 1e-12);
  EXPECT_NEAR(errors.uhi_distortion_error[1], 0.0001, 1e-12);
}

PinholeRadtanParameters rgbCamera(double fx, double fy, double cx, double cy) {
  PinholeRadtanParameters p;
  p.width = 960;
  p.height = 540;
  p.fx = fx;
  p.fy = fy;
  p.cx = cx;
  p.cy = cy;
  return p;
}

// The RGB intrinsics (hsmap's keys beside the contract's UHI ones): the
// survey's camera without an estimate, the run's with one; the focal error
// is the worse of fx and fy.
TEST(CalibrationMetrics, TheRgbCameraTheRunUsedIsScored) {
  TruthCalibration t = truth();
  t.rgb_camera = rgbCamera(800.0, 800.0, 479.5, 269.5);
  RunCalibration run;
  run.T_C_U.translation_m = Eigen::Vector3d(0.1, 0.0, 0.0);
  run.time_offset_s = 0.015;
  const PinholeRadtanParameters guess = rgbCamera(808.0, 804.0, 482.5, 267.5);
  CalibrationErrors errors = compareCalibration(run, camera(1500.0, 959.5, 0.01, -0.002), guess, t);
  EXPECT_NEAR(errors.rgb_focal_error_rel, 0.01, 1e-12);
  EXPECT_NEAR(errors.rgb_cx_error_px, 3.0, 1e-12);
  EXPECT_NEAR(errors.rgb_cy_error_px, 2.0, 1e-12);
  EXPECT_NEAR(errors.uhi_focal_error_rel, 0.0, 1e-12);
  RgbCameraEstimate estimate;
  estimate.fx = 800.4;
  estimate.fy = 799.2;
  estimate.cx = 479.7;
  estimate.cy = 269.4;
  run.rgb_camera = estimate;
  errors = compareCalibration(run, camera(1500.0, 959.5, 0.01, -0.002), guess, t);
  EXPECT_NEAR(errors.rgb_focal_error_rel, 0.001, 1e-12);
  EXPECT_NEAR(errors.rgb_cx_error_px, 0.2, 1e-9);
  EXPECT_NEAR(errors.rgb_cy_error_px, 0.1, 1e-9);
}

}  // namespace
}  // namespace hsmap
