#pragma once
// The front-end's files in the run folder, RUN/frontend/ (the format is
// documented in docs/SURVEY_FORMAT.md, "Intermediate files: frontend/"):
//
//   keyframes.csv     keyframe,frame,t,segment,x,y,z,qw,qx,qy,qz      T_F_C of each keyframe
//   observations.csv  keyframe,landmark,u,v                           every 2D observation (distorted px)
//   landmarks.csv     landmark,x,y,z,observations,keyframes           p_F; keyframes: ids separated by spaces
//   frames.csv        frame,t,posed,segment,x,y,z,qw,qx,qy,qz         T_F_C of every frame (pose cells
//                                                                     empty when posed = 0)
//   frame_stats.csv   frame,t,status,keyframe,tracked,inliers,new_corners,
//                     decode_ms,preprocess_ms,track_ms,detect_ms,pnp_ms,triangulate_ms,ba_ms
//   frame_observations.csv
//                     frame,landmark,u,v                              the 2D-3D correspondences each posed
//                                                                     frame's pose rests on (distorted px)
//   losses.csv        first_frame,last_frame,reason
//   segments.csv      segment,first_frame,last_frame,keyframes,reference,linked,
//                     scale,qw,qx,qy,qz,x,y,z,ins_rms_m,              S_F_S of each segment, and how it
//                     link,scale_sigma,joined_to,note                 was linked (reference, vision, ins,
//                                                                     none), scale 1-sigma, segment joined to
//   frames.tum        t tx ty tz qx qy qz qw                          posed frames only (TUM format)
//   summary.txt       the run's summary and warnings, for people
//
// Writing is atomic for the whole folder: everything goes to
// RUN/frontend.partial/ (each file through AtomicFile), which is renamed to
// RUN/frontend/ when complete, replacing an older one. Numbers are in
// shortest round-trip form (number_text.h), so read -> write is lossless.
// Text cells (reasons, notes) never contain commas: they are replaced by ';'.
//
// frame_observations.csv holds, for every posed frame (keyframes included),
// the landmarks its pose was computed from: the final PnP inliers after the
// motion-only refinement (the two-view start's landmarks for a segment's
// first two keyframes), sorted by frame then landmark, each pair once, only
// landmarks of landmarks.csv. u,v are floats (as KLT measured them) in their
// own shortest round-trip form. It lets a later stage re-pose every frame
// against refined landmarks. It is the folder's largest file: ~28 bytes a
// row, ~500 rows a posed frame on the simulated surveys (17.5 MB for the
// 1,201 frames of `rugged`); it is written and read a row at a time.
//
// readFrontendOutputs() reads the folder back into a FrontendResult (map,
// frames with their statistics, frame observations, losses, segments; not the
// timings totals or warnings), with the strict CSV rules of csv_table.h
// (losses.csv and frame_observations.csv may have no row): errors are
// InputError naming the file and line; a frame observation of a frame that
// is not posed or of a landmark not in landmarks.csv is one.

#include <filesystem>

#include "pipelines/frontend/frontend_result.h"

namespace hsmap {

namespace frontend_files {
inline constexpr const char* folder = "frontend";
inline constexpr const char* keyframes = "keyframes.csv";
inline constexpr const char* observations = "observations.csv";
inline constexpr const char* landmarks = "landmarks.csv";
inline constexpr const char* frames = "frames.csv";
inline constexpr const char* frame_stats = "frame_stats.csv";
inline constexpr const char* frame_observations = "frame_observations.csv";
inline constexpr const char* losses = "losses.csv";
inline constexpr const char* segments = "segments.csv";
inline constexpr const char* frames_tum = "frames.tum";
inline constexpr const char* summary = "summary.txt";
}  // namespace frontend_files

// Writes RUN/frontend/ (see above). Throws std::runtime_error on I/O failure.
void writeFrontendOutputs(const std::filesystem::path& run_folder, const FrontendResult& result);

// Reads RUN/frontend/. Throws InputError for a missing or malformed file.
FrontendResult readFrontendOutputs(const std::filesystem::path& run_folder);

}  // namespace hsmap
