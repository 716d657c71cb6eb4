#pragma once
// The contract's RUN/calibration.yaml names the run's variant (evaluate checks
// it against run.yaml), but a stage's own calibration.yaml names the method
// that made it: georef/calibration.yaml says `sequential` in a joint run too,
// so that the georef folder is the same whichever variant ran it
// (stage_fingerprints.h). Published from such a stage (a joint run stopped
// before its joint stage), the contract's file is a copy relabelled with the
// run's variant; otherwise it is publishFile's hard link.

#include <filesystem>
#include <string>

namespace hsmap {

// `to` becomes `from` with `variant` as its variant, atomically. Throws
// InputError when `from` does not read, std::filesystem_error on I/O.
void publishCalibration(const std::filesystem::path& from, const std::filesystem::path& to,
                        const std::string& variant);

}  // namespace hsmap
