#pragma once
// EvaluationInputs: everything `hsmap evaluate RUN --truth SURVEY/truth`
// compares, loaded and checked for consistency before any metric is computed
// (docs/EVALUATE.md):
//   - the survey (loadSurvey on the truth folder's parent) and its truth
//     (loadSurveyTruth);
//   - the run's RUN/run.yaml, RUN/trajectory/frames.csv,
//     RUN/trajectory/uhi_lines.csv and RUN/calibration.yaml.
// A metric computed on rows that do not correspond would be a confident
// wrong number, so every mismatch is an InputError naming the file, the row
// and what was expected (input_consistency.h), never a silent skip.

#include <filesystem>
#include <vector>

#include "core/survey/pose_tables.h"
#include "core/survey/run_calibration.h"
#include "core/survey/run_record.h"
#include "core/survey/survey.h"
#include "core/survey/survey_truth.h"

namespace hsmap {

struct EvaluationInputs {
  std::filesystem::path run_folder;
  std::filesystem::path survey_folder;
  Survey survey;
  SurveyTruth truth;
  RunRecord run;
  // Empty for a `stacked` run (no poses, no calibration: run.variant says so).
  std::vector<TimedPose> frames;  // T_W_C, row i = survey frame i
  std::vector<LinePose> lines;    // T_W_U, row k = scan line k
  RunCalibration calibration;
  // Findings that do not stop the evaluation (e.g. run.yaml names another survey folder).
  std::vector<std::string> warnings;
};

// `truth_folder` is SURVEY/truth. Throws InputError for a missing or malformed
// file and for any inconsistency between the run, the survey and the truth.
EvaluationInputs loadEvaluationInputs(const std::filesystem::path& run_folder,
                                      const std::filesystem::path& truth_folder);

}  // namespace hsmap
