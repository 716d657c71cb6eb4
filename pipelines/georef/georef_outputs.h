#pragma once
// A geo-referenced trajectory and map as files in one folder: what the
// georef stage writes into RUN/georef/ and the joint stage into RUN/joint/
// (docs/SURVEY_FORMAT.md, "Intermediate files"), and what every later stage
// reads back, so that each stage starts from the run folder alone:
//
//   frames.csv           t,x,y,z,qw,qx,qy,qz           T_W_C, every RGB frame
//   frames.tum           the same in TUM format (t tx ty tz qx qy qz qw)
//   uhi_lines.csv        line,t,x,y,z,qw,qx,qy,qz      T_W_U, every scan line
//   uhi_lines.tum        the same lines in TUM format
//   pose_sources.csv     kind,index,t,source           where each pose came from
//                        (vision, ins_bridged, ins_only, held)
//   calibration.yaml     T_C_U and d used for the lines
//   rejected_fixes.csv   fix,ins_line,t,offset_m,step  INS fixes left out (alignment,
//                        bundle adjustment); absent when none was
//   keyframes.csv, observations.csv, landmarks.csv
//                        the adjusted map in W (visual_map_files.h); absent
//                        without one (planar)
//   sparse.ply           the adjusted landmarks in W (when there are any)
//   map_placement.yaml   the 1-sigma of the map's scale and placement from the
//                        INS (map_placement.h); sequential only
//   summary.txt          the stage's summary, for people
//
// The run publishes the contract's files (trajectory/frames.csv, ...,
// calibration.yaml, map/sparse.ply) from the folder of the stage that gives
// the run's current answer (pipelines/run/stage_table.h).
//
// Writing is atomic for the whole folder: everything goes to FOLDER.partial/
// and is renamed to FOLDER when complete, replacing an older one. Numbers
// are in shortest round-trip form: read -> write is lossless.

#include <filesystem>
#include <string>
#include <vector>

#include "core/survey/run_calibration.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

namespace georef_files {
inline constexpr const char* frames = "frames.csv";
inline constexpr const char* frames_tum = "frames.tum";
inline constexpr const char* lines = "uhi_lines.csv";
inline constexpr const char* lines_tum = "uhi_lines.tum";
inline constexpr const char* pose_sources = "pose_sources.csv";
inline constexpr const char* calibration = "calibration.yaml";
inline constexpr const char* rejected_fixes = "rejected_fixes.csv";
inline constexpr const char* sparse_ply = "sparse.ply";
inline constexpr const char* summary = "summary.txt";
inline constexpr const char* map_placement = "map_placement.yaml";
}  // namespace georef_files

// The calibration.yaml warnings about result.rgb_camera (none without it):
// that it was estimated, and what the survey could not separate; each
// starts with "rgb_camera".
std::vector<std::string> rgbCameraWarnings(const GeorefResult& result);

// `to` with `from`'s rgb_camera and its warnings (those starting with
// "rgb_camera", in place of any `to` had): a later stage's calibration.yaml (refine, joint) carries
// the georef stage's RGB intrinsics, which it does not change.
void carryRgbCamera(const RunCalibration& from, RunCalibration& to);

// The calibration.yaml written for `result` (its T_C_U and d; `warnings`
// when given, else that the variant does not estimate them).

RunCalibration georefCalibration(const GeorefResult& result, std::vector<std::string> warnings = {});

// Writes `folder` (see above). `calibration` is written as calibration.yaml
// (georefCalibration(result) when not given). Throws std::runtime_error on an
// I/O failure.
void writeGeorefOutputs(const std::filesystem::path& folder, const GeorefResult& result);
void writeGeorefOutputs(const std::filesystem::path& folder, const GeorefResult& result,
                        const RunCalibration& calibration);

// Reads `folder` back: frames, lines and their sources, the map in W (and
// landmarks_W from it), T_C_U and d from calibration.yaml, the rejected fixes,
// the map's placement when the folder has it.
// Not the alignment, the bundle report or the warnings. Throws InputError for
// a missing or malformed file.
GeorefResult readGeorefOutputs(const std::filesystem::path& folder);

}  // namespace hsmap
