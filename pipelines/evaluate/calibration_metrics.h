#pragma once
// The calibration metrics of metrics.json: the run's estimate of the RGB-UHI
// extrinsic T_C_U and of the UHI time offset d against the truth, with no
// alignment (both are relative quantities, untouched by geo-referencing):
//   extrinsic_rotation_error_deg   angle of R_est^-1 R_true
//   extrinsic_translation_error_m  |t_est - t_true|
//   time_offset_error_s            |d_est - d_true|

#include "core/survey/run_calibration.h"
#include "core/survey/truth_files.h"

namespace hsmap {

struct CalibrationErrors {
  double extrinsic_rotation_error_deg = 0.0;
  double extrinsic_translation_error_m = 0.0;
  double time_offset_error_s = 0.0;
};

CalibrationErrors compareCalibration(const RunCalibration& estimate, const TruthCalibration& truth);

}  // namespace hsmap
