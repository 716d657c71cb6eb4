#pragma once
// Progress: a one-line progress report for long loops (frames, lines, tiles).
//
// Long stages must show that they are alive and how far they are. Progress
// prints "<label>: <done>/<total> <unit> (<percent>%), <rate> <unit>/s, ETA <s>"
// to a stream at most every `min_interval_s` seconds (and once at the end), so
// it costs nothing measurable inside hot loops. On a terminal the line is
// redrawn in place; otherwise (logs, CI) each report is its own line.

#include <chrono>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace hsmap {

class Progress {
 public:
  Progress(std::string label, std::int64_t total, std::string unit, std::ostream& out,
           double min_interval_s = 1.0);
  ~Progress();

  // Adds `count` finished items; reports if enough time has passed.
  void advance(std::int64_t count = 1);
  // Prints the final report (idempotent; also called by the destructor).
  void finish();

  std::int64_t done() const { return done_; }
  std::int64_t total() const { return total_; }
  // The text of a report for the current state (no newline), for tests and logs.
  std::string reportLine() const;

 private:
  using Clock = std::chrono::steady_clock;
  void report(bool final_report);

  std::string label_;
  std::int64_t total_;
  std::string unit_;
  std::ostream& out_;
  double min_interval_s_;
  bool in_place_;
  bool finished_ = false;
  std::int64_t done_ = 0;
  Clock::time_point start_;
  Clock::time_point last_report_;
};

}  // namespace hsmap
