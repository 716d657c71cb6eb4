#pragma once
// simulateSurvey: writes a complete synthetic survey folder with exact ground
// truth (docs/SIMULATOR.md), through the same writers hsmap uses for real
// data, so the survey loader cannot tell it from a real survey.
//
// Steps: build the seabed mesh and its Embree ray caster; fly the vehicle over
// it (terrain following); render every RGB frame (25 Hz) and every UHI scan
// line (30 Hz, exposed at recorded time + d) by ray casting; synthesise the
// INS (1 Hz) with noise and drift; write survey.yaml with a perturbed
// calibration guess; write truth/ (poses, true calibration, scene.ply, the
// reflectance ortho-image over the UHI footprint).
//
// The sensors record while the vehicle is inside its trajectory with a margin
// of 0.5 s + |d| at both ends, so every true UHI time has a pose; the INS
// covers the whole trajectory. Everything is written under "<folder>.partial"
// and renamed to `folder` at the end: an interrupted run leaves no folder
// that looks complete. Same configuration (and seed), same bytes.
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "pipelines/simulate/simulation_config.h"

namespace hsmap {

struct SimulationSummary {
  std::filesystem::path folder;
  std::size_t scene_triangles = 0;
  int rgb_frames = 0;
  int rgb_width = 0;
  int rgb_height = 0;
  std::string rgb_format;        // png, jpeg or h264 (rgb.encoding)
  std::uintmax_t rgb_bytes = 0;  // of the frame files or the video
  double rgb_rate_hz = 0.0;
  int uhi_lines = 0;
  int uhi_samples = 0;
  int uhi_bands = 0;
  int ins_fixes = 0;
  double survey_seconds = 0.0;  // from the first sensor record to the last
  int reflectance_rows = 0;
  int reflectance_cols = 0;
  std::int64_t reflectance_valid_pixels = 0;
  std::vector<std::pair<std::string, double>> stage_seconds;
  double peak_memory_mb = 0.0;
  // Several lines: what was written where, and how long each stage took.
  std::string toString() const;
};

// The seed of the scene's MaterialField, so that tests and tools can
// evaluate the true material field of a simulated survey.
std::uint64_t simulationMaterialSeed(const SimulationConfig& config);

// Throws std::invalid_argument for an invalid configuration (before writing
// anything) and std::runtime_error for I/O failures.
SimulationSummary simulateSurvey(const SimulationConfig& config, const std::filesystem::path& folder,
                                 std::ostream& log);

}  // namespace hsmap
