#pragma once
// The stages of `hsmap run` and the order each variant runs them in: the
// only place that knows it (docs/RUN.md). A stage is a function of its own
// options and the run folder (stage_context.h); stages never call each
// other. For each stage the table says:
//   - the files it owns in RUN (removed before it runs; their sizes are
//     recorded when it ends, for resuming: stage_record.h);
//   - the contract's files published from them (trajectory/*.csv,
//     calibration.yaml, map/*.ply): after the stage, each names the latest
//     stage's answer;
//   - the text of its options that its fingerprint covers (a change redoes
//     the stage and the ones after);
//   - the command-line options it reads, so that one a variant ignores is an
//     error.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "pipelines/run/run_options.h"
#include "pipelines/run/stage_context.h"

namespace hsmap {

enum class StageId { frontend, georef, surface, refine, joint, radiometry, products };

struct StageDefinition {
  StageId id;
  const char* name;
  // Relative to RUN: folders or files the stage writes.
  std::vector<std::filesystem::path> outputs;
  // (owned file, contract path), relative to RUN; an owned file the stage did
  // not write (map/sparse.ply of planar) is not published.
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> published;
  // The command-line options the stage reads.
  std::vector<std::string> command_options;
  // "key: value" lines of the options the stage's result depends on.
  std::string (*options_text)(const RunOptions& options);
  void (*run)(const StageContext& context, const RunOptions& options);
};

const std::vector<StageId>& variantStages(Variant variant);
// Every stage of any variant, in run order.
const std::vector<StageId>& allStages();
const StageDefinition& stageDefinition(StageId id);
// The stage named `name` among `stages`, or -1.
int stageIndex(const std::vector<StageId>& stages, const std::string& name);
// "frontend, georef, ..." for messages.
std::string stageList(const std::vector<StageId>& stages);

// Every contract path any stage publishes (removed at a run's start and
// published again as its stages end or are found up to date).
std::vector<std::filesystem::path> publishedContractPaths();

// The first command-line option in `options.given` that `options.variant`
// ignores, with the message naming it and the variant; empty when none.
std::string ignoredOptionError(const RunOptions& options);

}  // namespace hsmap
