#pragma once
// StageTimings: wall time of each named stage of a run, in the order the
// stages ran, so every command can end with a summary of where time went and
// metrics.json can report `timings_s`.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace hsmap {

class StageTimings {
 public:
  // Starts timing `name`; the returned guard records the elapsed wall time
  // when it is destroyed (or when stop() is called).
  class Guard {
   public:
    Guard(StageTimings& owner, std::string name);
    ~Guard();
    Guard(const Guard&) = delete;
    Guard& operator=(const Guard&) = delete;
    void stop();

   private:
    StageTimings* owner_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
    bool stopped_ = false;
  };

  Guard stage(std::string name) { return Guard(*this, std::move(name)); }
  void record(const std::string& name, double seconds);

  // Stages in first-run order; a stage run twice accumulates its time.
  const std::vector<std::pair<std::string, double>>& seconds() const { return seconds_; }
  double total() const;

 private:
  std::vector<std::pair<std::string, double>> seconds_;
};

// Wall seconds since `start` on the steady clock (for a stage's parts).
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Peak resident set size of this process so far, in MiB (getrusage).
double peakResidentMemoryMb();

}  // namespace hsmap
