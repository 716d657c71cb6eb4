#pragma once
// Which stages the variants of a compare share (docs/COMPARE.md). A stage's
// fingerprint depends only on its options, the survey and the stages before
// it (pipelines/run/stage_fingerprints.h), so two variants whose leading
// stages have the same fingerprints would compute the same folders: the
// later one takes them from the earlier one's run folder instead. With the
// default options that is `joint` taking `frontend`, `georef` and `surface`
// from `sequential`; `planar` (georef from the INS alone) and `stacked`
// (products alone) share nothing.

#include <optional>
#include <string>
#include <vector>

#include "pipelines/run/run_options.h"
#include "pipelines/run/stage_table.h"

namespace hsmap {

struct VariantPlan {
  Variant variant;
  // The variant earlier in the list whose run folder it takes stages from,
  // and those stages (its first ones, in order); none when it shares nothing.
  std::optional<Variant> donor;
  std::vector<StageId> shared;
};

// In the order given. Each variant's donor is the earlier variant with the
// longest run of leading stages of equal fingerprints (the first such on a
// tie). `base` holds the options every variant runs with (its variant is
// ignored); `survey_stamp` is surveyStamp() of the survey.
std::vector<VariantPlan> planCompare(const std::vector<Variant>& variants, const RunOptions& base,
                                     const std::string& survey_stamp);

}  // namespace hsmap
