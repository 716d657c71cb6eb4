#pragma once
// The `--variants` list of `hsmap compare`: variant names separated by
// commas, each at most once, in the order the table shows them.

#include <string>
#include <vector>

#include "pipelines/run/run_options.h"

namespace hsmap {

// Every variant, in the table's default order.
const std::vector<Variant>& allCompareVariants();

// Throws std::invalid_argument with the message the command prints, e.g.
//   --variants: unknown variant 'fused' in 'planar,fused'; expected names among stacked, planar, sequential, joint, separated by commas
//   --variants: 'joint' is listed twice in 'joint,joint'
//   --variants: expected at least one variant, got ''
std::vector<Variant> parseVariantList(const std::string& text);

}  // namespace hsmap
