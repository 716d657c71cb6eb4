#pragma once
// The calibration metrics of metrics.json: the run's estimate of the RGB-UHI
// extrinsic T_C_U and of the UHI time offset d against the truth, with no
// alignment (both are relative quantities, untouched by geo-referencing):
//   extrinsic_rotation_error_deg   angle of R_est^-1 R_true
//   extrinsic_translation_error_m  |t_est - t_true|
//   time_offset_error_s            |d_est - d_true|
// and of the UHI camera's intrinsics (calibration.yaml's uhi_camera when the
// run estimated them, survey.yaml's uhi.camera otherwise):
//   uhi_focal_error_rel            |f - f_true| / f_true
//   uhi_cx_error_px                |cx - cx_true|
//   uhi_distortion_error           |k_i - k_i,true| per coefficient (k1, k2)
// and of the RGB camera's (calibration.yaml's rgb_camera when the run
// estimated them, survey.yaml's rgb.camera otherwise; not named by the
// contract, in the UHI keys' style):
//   rgb_focal_error_rel            max(|fx - fx_true| / fx_true, |fy - fy_true| / fy_true)
//   rgb_cx_error_px, rgb_cy_error_px  |cx - cx_true|, |cy - cy_true|

#include <array>

#include "core/survey/run_calibration.h"
#include "core/survey/truth_files.h"

namespace hsmap {

struct CalibrationErrors {
  double extrinsic_rotation_error_deg = 0.0;
  double extrinsic_translation_error_m = 0.0;
  double time_offset_error_s = 0.0;
  double uhi_focal_error_rel = 0.0;
  double uhi_cx_error_px = 0.0;
  std::array<double, 2> uhi_distortion_error{0.0, 0.0};
  double rgb_focal_error_rel = 0.0;
  double rgb_cx_error_px = 0.0;
  double rgb_cy_error_px = 0.0;
};

// `survey_uhi_camera`: survey.yaml's uhi.camera, the run's camera when
// calibration.yaml has no uhi_camera.
CalibrationErrors compareCalibration(const RunCalibration& estimate, const PushbroomParameters& survey_uhi_camera,
                                     const TruthCalibration& truth);
// The same with the RGB camera's errors too (`survey_rgb_camera`:
// survey.yaml's rgb.camera, the run's when calibration.yaml has no rgb_camera).
CalibrationErrors compareCalibration(const RunCalibration& estimate, const PushbroomParameters& survey_uhi_camera,
                                     const PinholeRadtanParameters& survey_rgb_camera, const TruthCalibration& truth);

}  // namespace hsmap
