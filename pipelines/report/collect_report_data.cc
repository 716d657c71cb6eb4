#include "pipelines/report/collect_report_data.h"

#include <memory>
#include <stdexcept>

#include "core/survey/survey.h"
#include "core/util/input_error.h"
#include "pipelines/report/collect_images.h"
#include "pipelines/report/collect_residuals.h"
#include "pipelines/report/collect_run_summary.h"
#include "pipelines/report/collect_trajectory.h"
#include "pipelines/report/collect_truth.h"

namespace hsmap {

namespace fs = std::filesystem;

ReportData collectReportData(const fs::path& run) {
  std::error_code error;
  if (!fs::is_directory(run / "stages", error)) {
    throw std::runtime_error(run.string() + " is not a run folder: it has no stages/ (expected the folder of "
                             "`hsmap run SURVEY --out RUN`)");
  }
  ReportData data;
  data.run_folder = fs::absolute(run).lexically_normal().string();
  collectRunSummary(run, data);

  std::unique_ptr<Survey> survey;
  try {
    survey = std::make_unique<Survey>(loadSurvey(data.survey_folder));
    data.survey_uhi_camera = survey->config.uhi.camera;
    data.survey_rgb_camera = survey->config.rgb.camera;
    // The residuals through the RGB camera the run used: georef's estimate
    // when survey.yaml gives rgb.camera_sigma (docs/GEOREF.md).
    if (data.calibration && data.calibration->rgb_camera) {
      survey->config.rgb.camera = data.calibration->rgb_camera->appliedTo(survey->config.rgb.camera);
    }
    data.survey_name = survey->config.name;
    for (const std::string& warning : survey->warnings) data.warnings.insert(data.warnings.begin(), "survey: " + warning);
  } catch (const InputError& failure) {
    data.notes.push_back("the survey could not be read (" + std::string(failure.what()) +
                         "): the INS fixes and residuals are not shown");
  }
  collectTrajectory(run, survey.get(), data);
  collectResiduals(run, survey.get(), data);
  collectImages(run, data);
  collectTruth(run, data);
  return data;
}

}  // namespace hsmap
