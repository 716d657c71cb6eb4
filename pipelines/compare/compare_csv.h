#pragma once
// DIR/compare.csv: the compare table for scripts (docs/COMPARE.md).
//
//   key,better,best,stacked,planar,sequential,joint
//   status,,,ok,ok,ok,"failed: stage joint failed: ..."
//   shared_stages,,,,,,frontend georef surface
//   shared_from,,,,,,sequential
//   wall_time_s,lower,stacked,9.1,263.6,240.2,131.7
//   time_s.frontend,lower,sequential joint,,,71.5,71.5
//   rgb_ate_m,lower,sequential,,0.5,0.0123,0.0125
//
// One column per variant; `better` is lower, higher or empty (no best);
// `best` names the best variants of the row, separated by spaces; an empty
// cell is a missing figure; numbers in shortest round-trip form, so a script
// reads back exactly what metrics.json said. RFC 4180 quoting.

#include <filesystem>
#include <string>
#include <string_view>

#include "pipelines/compare/compare_table.h"

namespace hsmap {

std::string compareCsv(const CompareTable& table);
// Atomic (a temporary name renamed into place).
void writeCompareCsv(const std::filesystem::path& file, const CompareTable& table);

// The table back (rows, best marks and the variants' status, sharing, wall
// time, stage times and metrics; not the quick-looks). InputError naming the
// file, the line and what was expected.
CompareTable readCompareCsv(const std::filesystem::path& file);
CompareTable parseCompareCsv(std::string_view text, const std::filesystem::path& file);

}  // namespace hsmap
