#include "pipelines/run/estimated_rgb_camera.h"

#include <ostream>

#include "core/survey/run_calibration.h"

namespace hsmap {

bool useEstimatedRgbCamera(Survey& survey, const std::filesystem::path& calibration_yaml, std::ostream& out) {
  std::error_code error;
  if (!std::filesystem::exists(calibration_yaml, error)) return false;
  const RunCalibration calibration = readRunCalibration(calibration_yaml);
  if (!calibration.rgb_camera) return false;
  PinholeRadtanParameters& camera = survey.config.rgb.camera;
  camera = calibration.rgb_camera->appliedTo(camera);
  out << "the later stages use the RGB camera of " << calibration_yaml.string() << " (fx " << camera.fx << ", fy "
      << camera.fy << ", cx " << camera.cx << ", cy " << camera.cy << ", distortion [" << camera.distortion[0]
      << ", " << camera.distortion[1] << ", " << camera.distortion[2] << ", " << camera.distortion[3] << ", "
      << camera.distortion[4] << "])\n";
  return true;
}

}  // namespace hsmap
