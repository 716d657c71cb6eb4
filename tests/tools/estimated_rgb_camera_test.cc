// The runner's hand-over of the RGB camera georef estimated
// (pipelines/run/estimated_rgb_camera.h): the later stages see
// calibration.yaml's rgb_camera in survey.config.rgb.camera, with survey.yaml's
// model and image size, and survey.yaml's camera when there is none.
#include "pipelines/run/estimated_rgb_camera.h"

#include <gtest/gtest.h>

#include <sstream>

#include "core/survey/run_calibration.h"
#include "core/util/input_error.h"
#include "tests/support/temp_folder.h"

namespace hsmap {
namespace {

RunCalibration calibrationWithout() {
  RunCalibration calibration;
  calibration.variant = "sequential";
  return calibration;
}

PinholeRadtanParameters surveyCamera() {
  PinholeRadtanParameters camera;
  camera.width = 320;
  camera.height = 180;
  camera.fx = camera.fy = 269.0;
  camera.cx = 162.5;
  camera.cy = 89.0;
  camera.distortion = {-0.08, 0.02, 4e-4, -3e-4, 0.0};
  return camera;
}

TEST(EstimatedRgbCamera, TheLaterStagesSeeGeorefsEstimateWithTheSurveysImageSize) {
  testing::TempFolder temp("estimated_rgb_camera");
  const auto file = temp / "calibration.yaml";
  Survey survey;
  survey.config.rgb.camera = surveyCamera();
  std::ostringstream out;
  // No file (planar's georef wrote none yet) and a file without rgb_camera: unchanged.
  EXPECT_FALSE(useEstimatedRgbCamera(survey, file, out));
  writeRunCalibration(file, calibrationWithout());
  EXPECT_FALSE(useEstimatedRgbCamera(survey, file, out));
  EXPECT_EQ(survey.config.rgb.camera.fx, 269.0);
  EXPECT_TRUE(out.str().empty());

  RunCalibration calibration = calibrationWithout();
  RgbCameraEstimate estimate;
  estimate.fx = 266.5;
  estimate.fy = 266.75;
  estimate.cx = 159.75;
  estimate.cy = 89.25;
  estimate.distortion = {-0.079, 0.021, 4e-4, -3e-4, 0.0};
  calibration.rgb_camera = estimate;
  writeRunCalibration(file, calibration);
  EXPECT_TRUE(useEstimatedRgbCamera(survey, file, out));
  const PinholeRadtanParameters& used = survey.config.rgb.camera;
  EXPECT_EQ(used.width, 320);
  EXPECT_EQ(used.height, 180);
  EXPECT_EQ(used.fx, 266.5);
  EXPECT_EQ(used.fy, 266.75);
  EXPECT_EQ(used.cx, 159.75);
  EXPECT_EQ(used.cy, 89.25);
  EXPECT_EQ(used.distortion, estimate.distortion);
  EXPECT_NE(out.str().find("the later stages use the RGB camera of " + file.string() + " (fx 266.5, fy 266.75"),
            std::string::npos)
      << out.str();

  // A damaged file is an error naming it, not survey.yaml's camera in silence.
  testing::replaceInFile(file, "fx: 266.5,", "fx: -1,");
  EXPECT_THROW(useEstimatedRgbCamera(survey, file, out), InputError);
}

}  // namespace
}  // namespace hsmap
