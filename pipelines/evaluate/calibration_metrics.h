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
};

// `survey_uhi_camera`: survey.yaml's uhi.camera, the run's camera when
// calibration.yaml has no uhi_camera.
CalibrationErrors compareCalibration(const RunCalibration& estimate, const PushbroomParameters& survey_uhi_camera,
                                     const TruthCalibration& truth);

}  // namespace hsmap
