#include "core/survey/pose_tables.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/io/atomic_file.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"

namespace hsmap {
namespace {

// Pose tables are machine-written: a quaternion further than this from unit
// norm is damage, not rounding (see the header).
constexpr double kQuaternionNormTolerance = 1e-6;
// A few ulps of 1: the squared norm of a normalised quaternion lies within it,
// and such a quaternion is kept bit-exactly.
constexpr double kUnitSquaredNormSlack = 1e-15;

const std::vector<std::string> kTimedColumns = {"t", "x", "y", "z", "qw", "qx", "qy", "qz"};
const std::vector<std::string> kLineColumns = {"line", "t",  "x",  "y", "z",
                                               "qw",   "qx", "qy", "qz"};

std::string quaternionNormProblem(const Eigen::Quaterniond& q) {
  const double norm = q.norm();
  if (std::abs(norm - 1.0) <= kQuaternionNormTolerance) return "";
  return "expected a unit quaternion (norm within " + formatDouble(kQuaternionNormTolerance) +
         " of 1), got norm " + formatDouble(norm);
}

// Reads t, x, y, z, qw, qx, qy, qz starting at column `first` of `row`.
void readPose(const CsvTable& table, const CsvTable::Row& row, std::size_t first, double* t,
              SE3d* pose) {
  *t = table.number(row, first);
  const Eigen::Vector3d translation(table.number(row, first + 1), table.number(row, first + 2),
                                    table.number(row, first + 3));
  Eigen::Quaterniond q(table.number(row, first + 4), table.number(row, first + 5),
                       table.number(row, first + 6), table.number(row, first + 7));
  const std::string problem = quaternionNormProblem(q);
  if (!problem.empty()) {
    throw InputError(table.file, InputError::atLine(row.line_number),
                     "columns qw,qx,qy,qz: " + problem);
  }
  if (std::abs(q.squaredNorm() - 1.0) > kUnitSquaredNormSlack) q.normalize();
  *pose = SE3d(q, translation);
}

// Checks one pose the way the readers would, naming `caller` and the time.
void requireWritable(std::string_view caller, double t, const SE3d& pose) {
  const Eigen::Quaterniond& q = pose.q;
  for (double value : {t, pose.t.x(), pose.t.y(), pose.t.z(), q.w(), q.x(), q.y(), q.z()}) {
    if (!std::isfinite(value)) {
      throw std::invalid_argument(std::string(caller) + ": non-finite value at time " +
                                  formatDouble(t));
    }
  }
  const std::string problem = quaternionNormProblem(q);
  if (!problem.empty()) {
    throw std::invalid_argument(std::string(caller) + ": pose at time " + formatDouble(t) + ": " +
                                problem);
  }
}

void requireIncreasingTime(std::string_view caller, std::size_t index, double previous_t,
                           double t) {
  if (index > 0 && !(t > previous_t)) {
    throw std::invalid_argument(std::string(caller) + ": times must be strictly increasing, got " +
                                formatDouble(t) + " after " + formatDouble(previous_t));
  }
}

// "t,x,y,z,qw,qx,qy,qz" and a line end.
void appendCsvPose(std::string* text, double t, const SE3d& pose) {
  const Eigen::Quaterniond& q = pose.q;
  const double values[] = {t, pose.t.x(), pose.t.y(), pose.t.z(), q.w(), q.x(), q.y(), q.z()};
  for (std::size_t i = 0; i < 8; ++i) {
    if (i > 0) *text += ',';
    *text += formatDouble(values[i]);
  }
  *text += '\n';
}

// "t tx ty tz qx qy qz qw" and a line end: TUM puts the quaternion's w last.
void appendTumPose(std::string* text, double t, const SE3d& pose) {
  const Eigen::Quaterniond& q = pose.q;
  const double values[] = {t, pose.t.x(), pose.t.y(), pose.t.z(), q.x(), q.y(), q.z(), q.w()};
  for (std::size_t i = 0; i < 8; ++i) {
    if (i > 0) *text += ' ';
    *text += formatDouble(values[i]);
  }
  *text += '\n';
}

void writeAtomically(const std::filesystem::path& file, const std::string& text) {
  AtomicFile out(file);
  out.stream() << text;
  out.commit();
}

// Both timed writers check the same things; only the line format differs.
template <typename AppendPose>
void writeTimed(const std::filesystem::path& file, const std::vector<TimedPose>& poses,
                std::string_view caller, std::string text, AppendPose append) {
  if (poses.empty()) {
    throw std::invalid_argument(std::string(caller) + ": expected at least one pose");
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    requireIncreasingTime(caller, i, i > 0 ? poses[i - 1].t : 0.0, poses[i].t);
    requireWritable(caller, poses[i].t, poses[i].T);
    append(&text, poses[i].t, poses[i].T);
  }
  writeAtomically(file, text);
}

}  // namespace

std::vector<TimedPose> readTimedPoseTable(const std::filesystem::path& file) {
  const CsvTable table = readCsvTable(file, {kTimedColumns});
  std::vector<TimedPose> poses;
  poses.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    TimedPose pose;
    readPose(table, row, 0, &pose.t, &pose.T);
    if (!poses.empty()) checkTimeOrder(table, row, 0, poses.back().t, pose.t);
    poses.push_back(pose);
  }
  return poses;
}

std::vector<LinePose> readLinePoseTable(const std::filesystem::path& file) {
  const CsvTable table = readCsvTable(file, {kLineColumns});
  std::vector<LinePose> poses;
  poses.reserve(table.rows.size());
  for (const auto& row : table.rows) {
    LinePose pose;
    const long long expected = static_cast<long long>(poses.size());
    pose.line = table.integer(row, 0);
    if (pose.line != expected) {
      throw InputError(file, InputError::atLine(row.line_number),
                       "column 'line': expected scan line " + std::to_string(expected) +
                           " (one row per scan line, counting from 0 in order), got " +
                           std::to_string(pose.line));
    }
    readPose(table, row, 1, &pose.t, &pose.T);
    if (!poses.empty()) checkTimeOrder(table, row, 1, poses.back().t, pose.t);
    poses.push_back(pose);
  }
  return poses;
}

void writeTimedPoseTable(const std::filesystem::path& file, const std::vector<TimedPose>& poses,
                         std::string_view caller) {
  writeTimed(file, poses, caller, "t,x,y,z,qw,qx,qy,qz\n", appendCsvPose);
}

void writeTumTrajectory(const std::filesystem::path& file, const std::vector<TimedPose>& poses) {
  writeTimed(file, poses, "writeTumTrajectory", "", appendTumPose);
}

void writeLinePoseTable(const std::filesystem::path& file, const std::vector<LinePose>& poses,
                        std::string_view caller) {
  if (poses.empty()) {
    throw std::invalid_argument(std::string(caller) + ": expected at least one scan line");
  }
  std::string text = "line,t,x,y,z,qw,qx,qy,qz\n";
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (poses[i].line != static_cast<long long>(i)) {
      throw std::invalid_argument(std::string(caller) + ": expected scan line " +
                                  std::to_string(i) + " at position " + std::to_string(i) +
                                  ", got " + std::to_string(poses[i].line));
    }
    requireIncreasingTime(caller, i, i > 0 ? poses[i - 1].t : 0.0, poses[i].t);
    requireWritable(caller, poses[i].t, poses[i].T);
    text += std::to_string(poses[i].line) + ',';
    appendCsvPose(&text, poses[i].t, poses[i].T);
  }
  writeAtomically(file, text);
}

}  // namespace hsmap
