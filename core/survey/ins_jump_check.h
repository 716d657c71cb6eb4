#pragma once
// checkInsJumps: impossible and suspicious jumps between consecutive INS
// fixes of nav/ins.csv.
//
// Every fix can be in range on its own while the track is not: a longitude
// that jumps from 5° to 91° between fixes one second apart is a damaged
// file, not a vehicle. Two kinds of jump are told apart, on the geodesic
// distance between consecutive fixes (GeographicLib, WGS-84) and on depth:
//   - impossible: more than 1 km and faster than 50 m/s (no underwater
//     vehicle, and no acoustic positioning fix, moves so): an InputError
//     naming the line of the second fix;
//   - suspicious: more than a vehicle could move (3 m/s) plus six times the
//     fix noise (survey.yaml's sigma_horizontal_m / sigma_depth_m, at least
//     1 m): real INS logs hold such jumps (a USBL or DVL reset); they are
//     returned as warnings naming each line (the first five, then a count),
//     and geo-referencing treats such fixes as outliers.

#include <filesystem>
#include <string>
#include <vector>

#include "core/survey/csv_table.h"

namespace hsmap {

std::vector<std::string> checkInsJumps(const InsTable& ins, const std::filesystem::path& file,
                                       double sigma_horizontal_m, double sigma_depth_m);

}  // namespace hsmap
