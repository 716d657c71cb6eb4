#pragma once
// The number of threads the process's own parallel work may use
// (`hsmap run --threads N`): the solvers' Ceres threads read it whenever
// their options leave num_threads at 0, and the run sets oneTBB's limit to
// it too (tbb::global_control, held by the runner). 0, the default, means
// every hardware thread.
//
// One thread makes the solvers' sums run in one fixed order, so two runs
// give the same bits (docs/RUN.md, "Reproducing a run").

namespace hsmap {

// n >= 0 (0: every hardware thread); std::invalid_argument otherwise.
void setThreadBudget(int n);
// The budget resolved: n when set, else the hardware thread count (>= 1).
int threadBudget();

}  // namespace hsmap
