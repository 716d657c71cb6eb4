#include "pipelines/evaluate/calibration_metrics.h"

#include <cmath>

#include "pipelines/evaluate/trajectory_metrics.h"

namespace hsmap {

CalibrationErrors compareCalibration(const RunCalibration& estimate,
                                     const TruthCalibration& truth) {
  CalibrationErrors errors;
  errors.extrinsic_rotation_error_deg =
      rotationAngleDeg(estimate.T_C_U.rotation, truth.T_C_U.rotation);
  errors.extrinsic_translation_error_m =
      (estimate.T_C_U.translation_m - truth.T_C_U.translation_m).norm();
  errors.time_offset_error_s = std::abs(estimate.time_offset_s - truth.time_offset_s);
  return errors;
}

}  // namespace hsmap
