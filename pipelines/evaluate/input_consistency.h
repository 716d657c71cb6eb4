#pragma once
// The checks that make rows of a run, of the truth and of the survey
// correspond before they are compared (DATASET.md: "rows are matched to the
// truth by frame time stamp and by line index").
//
// Frames are matched by time within kFrameTimeTolerance (1 us: the contract
// asks for at least microsecond precision in copied times), in order, one row
// per survey frame. Scan lines are matched by index (the pose tables already
// number their rows 0, 1, 2, ...). Every check throws InputError naming the
// file, the 1-based text line of the offending row (data row k is on line
// k + 2, after the header) and the first frame or line that is missing or
// extra, with its time.

#include <filesystem>
#include <string>
#include <vector>

#include "core/survey/pose_tables.h"

namespace hsmap {

inline constexpr double kFrameTimeTolerance = 1e-6;  // seconds
// The true time of a scan line is recomputed as recorded + d: the same sum
// the simulator wrote, so only rounding separates the two.
inline constexpr double kLineTimeTolerance = 1e-6;  // seconds

// `poses` (the rows of `file`) hold exactly one pose per survey frame, at
// `frame_times` (which come from `frames_source`, named in messages).
void requireOneRowPerFrame(const std::vector<double>& frame_times,
                           const std::filesystem::path& frames_source,
                           const std::vector<TimedPose>& poses, const std::filesystem::path& file);

// `poses` (the rows of `file`) hold exactly scan lines 0 .. line_count - 1.
void requireEveryScanLine(std::size_t line_count, const std::filesystem::path& lines_source,
                          const std::vector<LinePose>& poses, const std::filesystem::path& file);

// Row k of `poses` (truth/uhi_poses.csv) holds t = line_times[k] + d, the
// line's true exposure time (d from `calibration_file`).
void requireTrueLineTimes(const std::vector<double>& line_times,
                          const std::filesystem::path& lines_source, double d,
                          const std::filesystem::path& calibration_file,
                          const std::vector<LinePose>& poses, const std::filesystem::path& file);

}  // namespace hsmap
