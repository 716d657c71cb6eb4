#pragma once
// The geo-referencing stage's products in the results folder (the data
// contract's "Results folder"; docs/SURVEY_FORMAT.md):
//
//   trajectory/frames.csv      t,x,y,z,qw,qx,qy,qz         T_W_C, every RGB frame
//   trajectory/frames.tum      the same in TUM format (t tx ty tz qx qy qz qw)
//   trajectory/uhi_lines.csv   line,t,x,y,z,qw,qx,qy,qz    T_W_U, every scan line
//   trajectory/uhi_lines.tum   the same lines in TUM format
//   trajectory/pose_sources.csv  kind,index,t,source     where each pose came from
//                              (vision, ins_bridged, ins_only, held)
//   calibration.yaml           T_C_U and d used for the lines (the survey's
//                              guesses: these variants do not estimate them,
//                              so their sigmas are null)
//   map/sparse.ply             the adjusted landmarks in W (sequential only)
//   georef/summary.txt         the stage's summary, for people
//
// All of them are written first into RUN/georef.partial/ and moved into
// place only once every one is complete, so a stage that fails leaves none
// of its products under its final name (an older run's are removed first).

#include <filesystem>
#include <vector>

#include "pipelines/georef/georef_result.h"

namespace hsmap {

// The relative paths writeGeorefOutputs() produces for `result`.
std::vector<std::filesystem::path> georefProductPaths(const GeorefResult& result);

// Throws std::runtime_error on an I/O failure.
void writeGeorefOutputs(const std::filesystem::path& run_folder, const GeorefResult& result);

}  // namespace hsmap
