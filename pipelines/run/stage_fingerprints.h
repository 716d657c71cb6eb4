#pragma once
// The fingerprint of every stage of a variant (docs/RUN.md, "Resuming"): a
// hash of the program's version, the stage's name and the text of its own
// options (stage_table.h), the survey's input files (surveyStamp,
// stage_record.h) and the previous stage's fingerprint.
//
// Nothing else goes in: in particular not the variant, unless a stage's
// result depends on it (then its options text says how, e.g. georef from the
// front-end's map or from the INS alone). So two variants that run the same
// stages with the same options on the same survey (sequential and joint up to
// surface) give those stages the same fingerprints, and a stage folder made
// by one is up to date in the other's run folder: `hsmap compare` runs them
// once.

#include <string>
#include <vector>

#include "pipelines/run/run_options.h"

namespace hsmap {

struct StageFingerprint {
  std::string options_text;  // what the fingerprint covers of the options
  std::string fingerprint;   // 16 hex digits
};

// One per stage of variantStages(options.variant), in run order.
std::vector<StageFingerprint> stageFingerprints(const RunOptions& options, const std::string& survey_stamp);

}  // namespace hsmap
