#include "pipelines/evaluate/calibration_metrics.h"

#include <algorithm>
#include <cmath>

#include "pipelines/evaluate/trajectory_metrics.h"

namespace hsmap {

CalibrationErrors compareCalibration(const RunCalibration& estimate, const PushbroomParameters& survey_uhi_camera,
                                     const TruthCalibration& truth) {
  CalibrationErrors errors;
  errors.extrinsic_rotation_error_deg =
      rotationAngleDeg(estimate.T_C_U.rotation, truth.T_C_U.rotation);
  errors.extrinsic_translation_error_m =
      (estimate.T_C_U.translation_m - truth.T_C_U.translation_m).norm();
  errors.time_offset_error_s = std::abs(estimate.time_offset_s - truth.time_offset_s);
  const PushbroomParameters camera =
      estimate.uhi_camera ? estimate.uhi_camera->appliedTo(survey_uhi_camera) : survey_uhi_camera;
  const PushbroomParameters& true_camera = truth.uhi_camera;
  errors.uhi_focal_error_rel = std::abs(camera.f - true_camera.f) / true_camera.f;
  errors.uhi_cx_error_px = std::abs(camera.cx - true_camera.cx);
  for (std::size_t i = 0; i < 2; ++i) {
    errors.uhi_distortion_error[i] = std::abs(camera.distortion[i] - true_camera.distortion[i]);
  }
  return errors;
}

CalibrationErrors compareCalibration(const RunCalibration& estimate, const PushbroomParameters& survey_uhi_camera,
                                     const PinholeRadtanParameters& survey_rgb_camera, const TruthCalibration& truth) {
  CalibrationErrors errors = compareCalibration(estimate, survey_uhi_camera, truth);
  const PinholeRadtanParameters camera =
      estimate.rgb_camera ? estimate.rgb_camera->appliedTo(survey_rgb_camera) : survey_rgb_camera;
  const PinholeRadtanParameters& true_camera = truth.rgb_camera;
  errors.rgb_focal_error_rel = std::max(std::abs(camera.fx - true_camera.fx) / true_camera.fx,
                                        std::abs(camera.fy - true_camera.fy) / true_camera.fy);
  errors.rgb_cx_error_px = std::abs(camera.cx - true_camera.cx);
  errors.rgb_cy_error_px = std::abs(camera.cy - true_camera.cy);
  return errors;
}

}  // namespace hsmap
