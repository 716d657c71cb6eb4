#include "pipelines/evaluate/input_consistency.h"

#include <cmath>

#include "core/survey/number_text.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

// The text line of data row `row` (0-based): the header is line 1.
std::string rowLine(std::size_t row) { return InputError::atLine(static_cast<long long>(row) + 2); }

std::string frameName(std::size_t index, double t) {
  return "frame " + std::to_string(index) + " of the survey (t = " + formatDouble(t) + ")";
}

}  // namespace

void requireOneRowPerFrame(const std::vector<double>& frame_times,
                           const std::filesystem::path& frames_source,
                           const std::vector<TimedPose>& poses,
                           const std::filesystem::path& file) {
  const std::string rule = "expected one row per frame of " + frames_source.string() +
                           ", at its time within " + formatDouble(kFrameTimeTolerance) + " s";
  // Both lists are strictly increasing (their readers check it), so one merge
  // pass finds the first frame without a row or the first row without a frame.
  std::size_t i = 0;  // survey frame
  std::size_t j = 0;  // row of `file`
  while (i < frame_times.size() && j < poses.size()) {
    const double t_frame = frame_times[i];
    const double t_row = poses[j].t;
    if (std::abs(t_row - t_frame) <= kFrameTimeTolerance) {
      ++i;
      ++j;
    } else if (t_row > t_frame) {
      throw InputError(file, rowLine(j),
                       "t = " + formatDouble(t_row) + ", but " + frameName(i, t_frame) +
                           " has no row before it: " + rule);
    } else {
      throw InputError(file, rowLine(j),
                       "t = " + formatDouble(t_row) + " is not the time of any frame (the next "
                       "one is " + frameName(i, t_frame) + "): an extra row; " + rule);
    }
  }
  if (i < frame_times.size()) {
    throw InputError(file, "",
                     std::to_string(poses.size()) + " rows, " + frameName(i, frame_times[i]) +
                         " and the " + std::to_string(frame_times.size() - i - 1) +
                         " after it have none: " + rule);
  }
  if (j < poses.size()) {
    throw InputError(file, rowLine(j),
                     "t = " + formatDouble(poses[j].t) + " is after the survey's last frame (" +
                         frameName(frame_times.size() - 1, frame_times.back()) +
                         "): an extra row; " + rule);
  }
}

void requireEveryScanLine(std::size_t line_count, const std::filesystem::path& lines_source,
                          const std::vector<LinePose>& poses,
                          const std::filesystem::path& file) {
  const std::string range = "0 to " + std::to_string(line_count - 1);
  if (poses.size() < line_count) {
    throw InputError(file, "",
                     "holds scan lines 0 to " + std::to_string(static_cast<long long>(poses.size()) - 1) +
                         ", expected every scan line of " + lines_source.string() + ", " + range +
                         ": line " + std::to_string(poses.size()) + " is missing");
  }
  if (poses.size() > line_count) {
    throw InputError(file, rowLine(line_count),
                     "scan line " + std::to_string(line_count) + " is not in the survey (" +
                         lines_source.string() + " holds lines " + range + ")");
  }
}

void requireTrueLineTimes(const std::vector<double>& line_times,
                          const std::filesystem::path& lines_source, double d,
                          const std::filesystem::path& calibration_file,
                          const std::vector<LinePose>& poses,
                          const std::filesystem::path& file) {
  for (std::size_t k = 0; k < poses.size() && k < line_times.size(); ++k) {
    const double expected = line_times[k] + d;
    if (std::abs(poses[k].t - expected) > kLineTimeTolerance) {
      throw InputError(file, rowLine(k),
                       "t = " + formatDouble(poses[k].t) + ", expected " + formatDouble(expected) +
                           " = scan line " + std::to_string(k) + "'s recorded time " +
                           formatDouble(line_times[k]) + " (" + lines_source.string() +
                           ") + time_offset_s " + formatDouble(d) + " (" +
                           calibration_file.string() + "), within " +
                           formatDouble(kLineTimeTolerance) + " s");
    }
  }
}

}  // namespace hsmap
