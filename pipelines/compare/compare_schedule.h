#pragma once
// The order and concurrency of a compare's runs (docs/COMPARE.md). A variant
// that others take stages from (compare_plan.h) runs in two steps: its shared
// stages first (`hsmap run --until` the last of them), then the rest (the
// same run again: it resumes after them); the variants that take them start
// as soon as the first step is done, beside the second. Every other variant
// is one step. Up to `jobs` steps run at once: one run uses about half of a
// two-core machine on average (reading the cube, writing the products), so
// two runs side by side finish sooner than one after the other.

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "pipelines/compare/compare_plan.h"

namespace hsmap {

struct CompareTask {
  std::size_t variant = 0;        // index in the plans
  std::string until;              // non-empty: only up to this stage (the shared ones)
  std::vector<std::size_t> after;  // tasks that must have finished first
};

// The shared-stage steps first, then the variants that take stages, then the
// others in the plans' order: the order in which ready tasks start.
std::vector<CompareTask> scheduleCompare(const std::vector<VariantPlan>& plans);

// Calls `run(task)` for every task once all of its `after` have returned, at
// most `jobs` at a time (from as many threads), ready tasks in their order.
// `run` must not throw.
void runTaskGraph(const std::vector<CompareTask>& tasks, int jobs, const std::function<void(std::size_t)>& run);

}  // namespace hsmap
