#pragma once
// The RGB camera a run's later stages use: survey.yaml's rgb.camera, or the
// intrinsics the georef stage's bundle adjustment estimated when survey.yaml
// gives rgb.camera_sigma (RUN/georef/calibration.yaml's rgb_camera,
// docs/GEOREF.md "The RGB camera's intrinsics"). The runner applies it to
// the survey it hands every stage after georef (surface, refine, joint,
// products, radiometry), whether georef ran or was up to date, so a resumed
// run sees the same camera as a full one.

#include <filesystem>
#include <iosfwd>

#include "core/survey/survey.h"

namespace hsmap {

// Sets survey.config.rgb.camera to the rgb_camera of `calibration_yaml`
// when that file exists and has one (and says so on `out`); leaves it
// otherwise. Returns whether it changed. Throws InputError for a damaged file.
bool useEstimatedRgbCamera(Survey& survey, const std::filesystem::path& calibration_yaml, std::ostream& out);

}  // namespace hsmap
