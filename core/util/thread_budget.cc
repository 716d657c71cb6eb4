#include "core/util/thread_budget.h"

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

namespace hsmap {

namespace {
std::atomic<int> budget{0};
}  // namespace

void setThreadBudget(int n) {
  if (n < 0) throw std::invalid_argument("setThreadBudget: expected n >= 0, got " + std::to_string(n));
  budget.store(n);
}

int threadBudget() {
  const int n = budget.load();
  if (n > 0) return n;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware == 0 ? 1 : static_cast<int>(hardware);
}

}  // namespace hsmap
