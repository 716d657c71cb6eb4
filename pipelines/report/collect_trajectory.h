#pragma once
// The trajectory section's data: every frame's camera centre
// (trajectory/frames.csv), the adjusted map's keyframes (georef/keyframes.csv,
// or joint/'s for the joint variant), the survey's INS fixes in W with those
// geo-referencing left out (georef/rejected_fixes.csv) marked, and the
// front-end's tracking losses (frontend/losses.csv) at their frames' times.

#include <filesystem>

#include "pipelines/report/report_data.h"

namespace hsmap {

struct Survey;

// The folder of the run's adjusted map: joint/ for the joint variant when it
// is there, georef/ otherwise.
std::filesystem::path adjustedMapFolder(const std::filesystem::path& run, const std::string& variant);

// Fills frames, keyframes, ins_fixes (when `survey` is not null) and losses;
// a file that is absent adds a note. InputError for a malformed file.
void collectTrajectory(const std::filesystem::path& run, const Survey* survey, ReportData& data);

}  // namespace hsmap
