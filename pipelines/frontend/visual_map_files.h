#pragma once
// A VisualMap as three CSV files in a folder (the format of docs/SURVEY_FORMAT.md,
// "Intermediate files: frontend/"):
//
//   keyframes.csv     keyframe,frame,t,segment,x,y,z,qw,qx,qy,qz   the keyframe poses T_F_C
//   observations.csv  keyframe,landmark,u,v                        every 2D observation (distorted px)
//   landmarks.csv     landmark,x,y,z,observations,keyframes        p_F; keyframes: ids separated by spaces
//
// The front-end writes its map (frame F) this way, and geo-referencing its
// adjusted map (frame W) in RUN/georef/, so that every later stage reads the
// map it starts from out of the run folder. Numbers are in shortest
// round-trip form: read -> write is lossless.

#include <filesystem>

#include "pipelines/frontend/visual_map.h"

namespace hsmap {

namespace visual_map_files {
inline constexpr const char* keyframes = "keyframes.csv";
inline constexpr const char* observations = "observations.csv";
inline constexpr const char* landmarks = "landmarks.csv";
}  // namespace visual_map_files

// Writes the three files into `folder` (which must exist), each atomically.
// Throws std::runtime_error on an I/O failure.
void writeVisualMapFiles(const std::filesystem::path& folder, const VisualMap& map);

// Reads them back. Throws InputError naming the file and line for a missing
// or malformed file (ids out of order, an observation of an unknown keyframe
// or landmark, a landmark whose observation count disagrees).
VisualMap readVisualMapFiles(const std::filesystem::path& folder);

}  // namespace hsmap
