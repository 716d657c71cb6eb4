#include "pipelines/compare/compare_plan.h"

#include "pipelines/run/stage_fingerprints.h"

namespace hsmap {

std::vector<VariantPlan> planCompare(const std::vector<Variant>& variants, const RunOptions& base,
                                     const std::string& survey_stamp) {
  std::vector<std::vector<StageFingerprint>> fingerprints;
  for (Variant variant : variants) {
    RunOptions options = base;
    options.variant = variant;
    fingerprints.push_back(stageFingerprints(options, survey_stamp));
  }
  std::vector<VariantPlan> plans;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    VariantPlan plan{variants[i], std::nullopt, {}};
    std::size_t longest = 0;
    for (std::size_t j = 0; j < i; ++j) {
      std::size_t common = 0;
      while (common < fingerprints[i].size() && common < fingerprints[j].size() &&
             fingerprints[i][common].fingerprint == fingerprints[j][common].fingerprint) {
        ++common;
      }
      if (common > longest) {
        longest = common;
        plan.donor = variants[j];
      }
    }
    const std::vector<StageId>& stages = variantStages(variants[i]);
    plan.shared.assign(stages.begin(), stages.begin() + std::ptrdiff_t(longest));
    plans.push_back(std::move(plan));
  }
  return plans;
}

}  // namespace hsmap
