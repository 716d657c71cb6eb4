#include "core/util/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <ostream>

namespace hsmap {
namespace {
// Redrawing a line in place only makes sense on an interactive terminal.
bool isTerminal(const std::ostream& out) {
  if (&out == &std::cerr) return ::isatty(STDERR_FILENO) == 1;
  if (&out == &std::cout) return ::isatty(STDOUT_FILENO) == 1;
  return false;
}
}  // namespace

Progress::Progress(std::string label, std::int64_t total, std::string unit, std::ostream& out,
                   double min_interval_s)
    : label_(std::move(label)),
      total_(total),
      unit_(std::move(unit)),
      out_(out),
      min_interval_s_(min_interval_s),
      in_place_(isTerminal(out)),
      start_(Clock::now()),
      last_report_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(std::int64_t count) {
  done_ += count;
  const double since_last = std::chrono::duration<double>(Clock::now() - last_report_).count();
  // Completion is reported once, by finish(), not also by a periodic report.
  const bool complete = total_ > 0 && done_ >= total_;
  if (since_last >= min_interval_s_ && !complete) report(false);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  report(true);
}

std::string Progress::reportLine() const {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(done_) / elapsed : 0.0;
  char buffer[256];
  std::string text = label_ + ": " + std::to_string(done_);
  if (total_ > 0) {
    const double percent = 100.0 * static_cast<double>(done_) / static_cast<double>(total_);
    std::snprintf(buffer, sizeof buffer, "/%lld %s (%.0f%%)", static_cast<long long>(total_),
                  unit_.c_str(), percent);
  } else {
    std::snprintf(buffer, sizeof buffer, " %s", unit_.c_str());
  }
  text += buffer;
  std::snprintf(buffer, sizeof buffer, ", %.1f %s/s", rate, unit_.c_str());
  text += buffer;
  if (total_ > 0 && done_ < total_ && rate > 0) {
    std::snprintf(buffer, sizeof buffer, ", ETA %.0f s",
                  static_cast<double>(total_ - done_) / rate);
    text += buffer;
  } else if (done_ >= total_ && total_ > 0) {
    std::snprintf(buffer, sizeof buffer, ", done in %.2f s", elapsed);
    text += buffer;
  }
  return text;
}

void Progress::report(bool final_report) {
  last_report_ = Clock::now();
  if (in_place_) {
    out_ << '\r' << reportLine() << "\x1b[K";
    if (final_report) out_ << '\n';
  } else {
    out_ << reportLine() << '\n';
  }
  out_.flush();
}

}  // namespace hsmap
