#pragma once
// The `planar` variant's trajectory: the classical mosaic's, from the INS
// alone. Every frame's T_W_C(t) = T_W_B(t) T_B_C with the body pose
// interpolated between fixes (attitude from the INS, or level and along the
// track when it has none: ins_body_track.h), and every scan line's through
// the extrinsic and time-offset guesses. No vision, so no landmarks.

#include "core/survey/survey.h"
#include "pipelines/georef/georef_options.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

GeorefResult runPlanarGeoref(const Survey& survey, const GeorefOptions& options);

}  // namespace hsmap
