#include "core/util/stage_timer.h"

#include <sys/resource.h>

#include <algorithm>

namespace hsmap {

StageTimings::Guard::Guard(StageTimings& owner, std::string name)
    : owner_(&owner), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}

StageTimings::Guard::~Guard() { stop(); }

void StageTimings::Guard::stop() {
  if (stopped_) return;
  stopped_ = true;
  owner_->record(name_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

void StageTimings::record(const std::string& name, double seconds) {
  auto it = std::find_if(seconds_.begin(), seconds_.end(),
                         [&](const auto& entry) { return entry.first == name; });
  if (it == seconds_.end()) {
    seconds_.emplace_back(name, seconds);
  } else {
    it->second += seconds;
  }
}

double StageTimings::total() const {
  double sum = 0.0;
  for (const auto& [name, s] : seconds_) sum += s;
  return sum;
}

double peakResidentMemoryMb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace hsmap
