#pragma once
// The two pose tables that hsmap reads and writes wherever a trajectory is a
// file (docs/SURVEY_FORMAT.md): the survey's truth/ and a run's trajectory/.
//
//   timed table  t,x,y,z,qw,qx,qy,qz        T_W_X of sensor X at time t
//                (truth/rgb_poses.csv, RUN/trajectory/frames.csv)
//   line table   line,t,x,y,z,qw,qx,qy,qz   T_W_U of scan line `line` at time t
//                (truth/uhi_poses.csv, RUN/trajectory/uhi_lines.csv)
//
// x,y,z is the position of X in W and qw..qz the Hamilton quaternion R_W_X.
// One reader and one writer per table, so that the truth and the results
// cannot drift apart in format or in checks.
//
// Reading follows csv_table.h (exact header, cell count, finite numbers,
// errors naming the file and the 1-based line), plus:
//   - times strictly increase from row to row (matching frames by time and
//     interpolating poses both rely on it);
//   - the quaternion has a norm within 1e-6 of 1. These files are written by
//     programs, so a larger deviation means damage or columns in the wrong
//     order, not hand-typed digits. A quaternion that is unit to double
//     precision is kept bit-exactly (write -> read is an identity); one off by
//     more (but within 1e-6) is normalised;
//   - the line table numbers its rows 0, 1, 2, ... like uhi/lines.csv, so row
//     k (text line k + 2) is scan line k.
// Errors are InputError, e.g.
//   "RUN/trajectory/frames.csv:line 4: columns qw,qx,qy,qz: expected a unit
//    quaternion (norm within 1e-06 of 1), got norm 1.5".
//
// Writing: numbers in shortest round-trip form (number_text.h), so
// write -> read -> write gives the same bytes; atomic (AtomicFile: the file
// appears under its name only when complete). A writer throws
// std::invalid_argument "<caller>: ..." for data its reader would refuse
// (no rows, non-finite values, times not increasing, non-unit quaternions,
// lines not counting from 0), so hsmap never writes a table it cannot read.
// `caller` names the public function in those messages (truth_files.h passes
// its own names).
//
// writeTumTrajectory: the TUM RGB-D benchmark's text trajectory, read by evo
// and most SLAM tools: one line "t tx ty tz qx qy qz qw" per pose (quaternion
// LAST, w last), space-separated, no header, same number form and checks.

#include <filesystem>
#include <string_view>
#include <vector>

#include "core/geometry/se3.h"

namespace hsmap {

// The pose T_W_X of a sensor X (the RGB camera C in frames tables) at time t.
struct TimedPose {
  double t = 0.0;
  SE3d T;  // T_W_X
};

// The pose T_W_U of the UHI frame for scan line `line`, holding at time t.
struct LinePose {
  long long line = 0;
  double t = 0.0;
  SE3d T;  // T_W_U
};

// Throws InputError (see above).
std::vector<TimedPose> readTimedPoseTable(const std::filesystem::path& file);
std::vector<LinePose> readLinePoseTable(const std::filesystem::path& file);

// Throws std::invalid_argument for data the readers would refuse;
// std::runtime_error when the file cannot be written.
void writeTimedPoseTable(const std::filesystem::path& file, const std::vector<TimedPose>& poses,
                         std::string_view caller = "writeTimedPoseTable");
void writeLinePoseTable(const std::filesystem::path& file, const std::vector<LinePose>& poses,
                        std::string_view caller = "writeLinePoseTable");
void writeTumTrajectory(const std::filesystem::path& file, const std::vector<TimedPose>& poses);

}  // namespace hsmap
