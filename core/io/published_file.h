#pragma once
// publishFile: the run's contract files (trajectory/*.csv, calibration.yaml,
// map/mesh.ply, ...) are published from the folder of the stage that made
// them (RUN/georef/, RUN/refine/, RUN/joint/, RUN/surface/), so that each
// stage's own files stay as it wrote them for the stages that read them
// later, whichever stage gives the run's current answer.
//
// `to` becomes the same content as `from`: a hard link (no copy: the files
// are never modified in place, only replaced by rename), or a copy where the
// file system refuses links. It goes to `to`.partial first and is renamed
// onto `to`, so `to` is never half-written. Throws std::filesystem_error.

#include <filesystem>

namespace hsmap {

void publishFile(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace hsmap
