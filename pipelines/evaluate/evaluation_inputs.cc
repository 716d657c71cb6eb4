#include "pipelines/evaluate/evaluation_inputs.h"

#include <system_error>

#include "core/io/results_folder.h"
#include "core/util/input_error.h"
#include "core/util/message_text.h"
#include "pipelines/evaluate/input_consistency.h"

namespace hsmap {
namespace {

// A missing results file is reported by name with what writes it, before a
// reader's generic "cannot open" would be.
void requireResultsFile(const std::filesystem::path& file, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(file, error)) {
    throw InputError(file, "",
                     "missing: expected " + what + ", written by `hsmap run` (docs/EVALUATE.md)");
  }
}

// SURVEY/truth -> SURVEY. The folder must be called truth/: loadSurveyTruth
// reads SURVEY/truth, and evaluating against another folder than the one
// named would be a silent surprise.
std::filesystem::path surveyOfTruthFolder(const std::filesystem::path& truth_folder) {
  std::filesystem::path folder = truth_folder.lexically_normal();
  if (!folder.has_filename() && folder.has_parent_path()) folder = folder.parent_path();
  if (folder.filename() != "truth") {
    throw InputError(truth_folder, "",
                     "expected the truth/ folder of a simulated survey (SURVEY/truth), got a "
                     "folder named " + quoteForMessage(folder.filename().string()));
  }
  return folder.has_parent_path() ? folder.parent_path() : std::filesystem::path(".");
}

// run.yaml may name the survey by another path (a moved or copied folder):
// worth a warning, not a refusal, since rows are checked one by one anyway.
void compareSurveyPaths(EvaluationInputs* inputs) {
  std::error_code error;
  if (!std::filesystem::equivalent(inputs->run.survey, inputs->survey_folder, error)) {
    inputs->warnings.push_back("run.yaml names the survey " + inputs->run.survey.string() +
                               ", evaluating against " + inputs->survey_folder.string());
  }
}

}  // namespace

EvaluationInputs loadEvaluationInputs(const std::filesystem::path& run_folder,
                                      const std::filesystem::path& truth_folder) {
  EvaluationInputs inputs;
  inputs.run_folder = run_folder;
  std::error_code error;
  if (!std::filesystem::is_directory(run_folder, error)) {
    throw InputError(run_folder, "",
                     "missing: expected a results folder written by `hsmap run ... --out RUN`");
  }
  inputs.survey_folder = surveyOfTruthFolder(truth_folder);
  inputs.survey = loadSurvey(inputs.survey_folder);
  inputs.truth = loadSurveyTruth(inputs.survey_folder);

  // The truth must describe this survey: one pose per frame at its time, one
  // per scan line at its true time.
  const Survey& survey = inputs.survey;
  const std::filesystem::path frames_source = survey.rgb.sourcePath();
  {
    std::vector<TimedPose> truth_frames;
    for (const TruthPose& pose : inputs.truth.rgb_poses) truth_frames.push_back({pose.t, pose.T_W_X});
    requireOneRowPerFrame(survey.rgb.times(), frames_source, truth_frames,
                          inputs.truth.rgb_poses_path);
    std::vector<LinePose> truth_lines;
    for (const TruthLinePose& pose : inputs.truth.uhi_poses) {
      truth_lines.push_back({pose.line, pose.t, pose.T_W_U});
    }
    requireEveryScanLine(survey.line_times.size(), survey.lines_path, truth_lines,
                         inputs.truth.uhi_poses_path);
    requireTrueLineTimes(survey.line_times, survey.lines_path,
                         inputs.truth.calibration.time_offset_s, inputs.truth.calibration_path,
                         truth_lines, inputs.truth.uhi_poses_path);
  }

  const std::filesystem::path run_yaml = run_folder / results_paths::run_yaml;
  const std::filesystem::path frames_csv = run_folder / results_paths::trajectory_frames;
  const std::filesystem::path lines_csv = run_folder / results_paths::trajectory_uhi_lines;
  const std::filesystem::path calibration_yaml = run_folder / results_paths::calibration_yaml;
  requireResultsFile(run_yaml, "the run record run.yaml");
  inputs.run = readRunRecord(run_yaml);
  // The stacked variant poses nothing: it has no trajectory or calibration.
  if (inputs.run.variant == "stacked") {
    compareSurveyPaths(&inputs);
    return inputs;
  }
  requireResultsFile(frames_csv, "the pose of every RGB frame (t,x,y,z,qw,qx,qy,qz)");
  requireResultsFile(lines_csv, "the pose of every scan line (line,t,x,y,z,qw,qx,qy,qz)");
  requireResultsFile(calibration_yaml, "the estimated calibration calibration.yaml");

  inputs.frames = readTimedPoseTable(frames_csv);
  requireOneRowPerFrame(survey.rgb.times(), frames_source, inputs.frames, frames_csv);
  inputs.lines = readLinePoseTable(lines_csv);
  requireEveryScanLine(survey.line_times.size(), survey.lines_path, inputs.lines, lines_csv);
  inputs.calibration = readRunCalibration(calibration_yaml);
  if (inputs.calibration.variant != inputs.run.variant) {
    // Two files of different runs in one folder: whichever metric is right,
    // metrics.json would label it wrongly.
    throw InputError(calibration_yaml, InputError::atKey("variant"),
                     "variant " + quoteForMessage(inputs.calibration.variant) +
                         " differs from the variant " + quoteForMessage(inputs.run.variant) +
                         " of " + run_yaml.string() + "; expected the files of one run");
  }
  compareSurveyPaths(&inputs);
  return inputs;
}

}  // namespace hsmap
