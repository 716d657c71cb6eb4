#pragma once
// The radiometry stage's files in the run folder (docs/RADIOMETRY.md): the
// stage writes them, the products stage reads the estimate to turn the
// radiance ortho into reflectance.

namespace hsmap::radiometry_files {

inline constexpr const char* folder = "radiometry";
inline constexpr const char* water = "water.yaml";
inline constexpr const char* summary = "summary.txt";
inline constexpr const char* calibration = "calibration.yaml";

}  // namespace hsmap::radiometry_files
