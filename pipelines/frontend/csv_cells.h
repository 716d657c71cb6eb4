#pragma once
// The cells of the front-end's CSV files (frontend_outputs.h,
// visual_map_files.h), written and read the same way by both: numbers in
// shortest round-trip form, poses as x,y,z,qw,qx,qy,qz, errors as InputError
// naming the file and line.

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "core/geometry/se3.h"
#include "core/io/atomic_file.h"
#include "core/survey/csv_table.h"
#include "core/survey/number_text.h"
#include "core/util/input_error.h"

namespace hsmap::csv_cells {

inline std::string header(const std::vector<std::string>& columns) {
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) text += (i ? "," : "") + columns[i];
  return text + "\n";
}

inline std::string number(double value) { return formatDouble(value); }

inline std::string pose(const SE3d& T) {
  return number(T.t.x()) + "," + number(T.t.y()) + "," + number(T.t.z()) + "," + number(T.q.w()) + "," +
         number(T.q.x()) + "," + number(T.q.y()) + "," + number(T.q.z());
}

inline void writeFile(const std::filesystem::path& path, const std::string& text) { writeTextAtomically(path, text); }

[[noreturn]] inline void bad(const CsvTable& table, const CsvTable::Row& row, const std::string& detail) {
  throw InputError(table.file, InputError::atLine(row.line_number), detail);
}

// The pose starting at column `first`; its quaternion must be a unit one
// (it is not normalised: a written pose reads back bit for bit).
inline SE3d readPose(const CsvTable& table, const CsvTable::Row& row, std::size_t first) {
  const Eigen::Vector3d t(table.number(row, first), table.number(row, first + 1),
                          table.number(row, first + 2));
  const Eigen::Quaterniond q(table.number(row, first + 3), table.number(row, first + 4),
                             table.number(row, first + 5), table.number(row, first + 6));
  if (std::abs(q.norm() - 1.0) > 1e-6) bad(table, row, "columns qw,qx,qy,qz: expected a unit quaternion");
  return SE3d(q, t);
}

inline int id(const CsvTable& table, const CsvTable::Row& row, std::size_t column) {
  return static_cast<int>(table.integer(row, column));
}

}  // namespace hsmap::csv_cells
