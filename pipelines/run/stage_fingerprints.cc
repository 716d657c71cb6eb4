#include "pipelines/run/stage_fingerprints.h"

#include "pipelines/run/stage_record.h"
#include "pipelines/run/stage_table.h"

#ifndef HSMAP_VERSION
#define HSMAP_VERSION "unknown"
#endif

namespace hsmap {

std::vector<StageFingerprint> stageFingerprints(const RunOptions& options, const std::string& survey_stamp) {
  std::vector<StageFingerprint> stages;
  for (StageId id : variantStages(options.variant)) {
    const StageDefinition& stage = stageDefinition(id);
    StageFingerprint next;
    next.options_text = stage.options_text(options);
    next.fingerprint = fingerprintOf(std::string("hsmap ") + HSMAP_VERSION + "\nstage: " + stage.name + "\n" +
                                     next.options_text + "survey:\n" + survey_stamp + "previous: " +
                                     (stages.empty() ? std::string() : stages.back().fingerprint));
    stages.push_back(std::move(next));
  }
  return stages;
}

}  // namespace hsmap
