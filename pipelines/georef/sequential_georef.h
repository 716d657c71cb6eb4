#pragma once
// The `sequential` variant's geo-referencing (the reference paper's fusion):
//   1. the front-end's posed frames are aligned onto the INS by a robust
//      similarity at the fixes' own times (ins_alignment.h);
//   2. one bundle adjustment of all keyframes and landmarks with the INS
//      position (and attitude) factors, each fix at its own time, faulty
//      fixes tested and left out (georef_bundle_adjuster.h);
//   3. every frame the front-end posed is posed again by PnP against the
//      adjusted landmarks (frame_reposer.h);
//   4. frames the front-end could not pose are bridged by the INS between
//      their posed neighbours, and every scan line is posed at its recorded
//      time + the time-offset guess through the extrinsic guess
//      (camera_trajectory.h, scan_line_poses.h).
//
// Throws std::runtime_error when the survey cannot be geo-referenced (too
// few fixes within vision, nothing consistent, a failed solve), naming why.

#include <functional>
#include <string>

#include "core/survey/ins_body_track.h"
#include "core/survey/survey.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/georef/georef_bundle_adjuster.h"
#include "pipelines/georef/georef_options.h"
#include "pipelines/georef/georef_result.h"

namespace hsmap {

// Called with a step name and (done, total) counts, e.g. ("frames", 120, 1201).
using GeorefProgress = std::function<void(const std::string& step, int done, int total)>;

// The INS noise the bundle adjustment (and the joint problem) weighs the
// fixes with: survey.yaml's sigmas, the position sigmas inflated by the
// correlation factor sqrt(ins_correlation_time_s / median fix interval)
// (at least 1; georef_options.h).
InsNoise surveyInsNoise(const Survey& survey, const InsBodyTrack& ins, const GeorefOptions& options);

GeorefResult runSequentialGeoref(const Survey& survey, const FrontendResult& frontend,
                                 const GeorefOptions& options,
                                 const GeorefProgress& progress = {});

}  // namespace hsmap
