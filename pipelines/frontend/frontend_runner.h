#pragma once
// runFrontend: the first stage of `hsmap run` — the monocular visual
// front-end (docs/FRONTEND.md). From the survey's RGB frames alone it poses
// every frame it can (up to scale, in the front-end's frame F) and builds a
// sparse map of keyframes, landmarks and their 2D observations; the INS is
// used only to link map segments across tracking losses (segment_linker.h).
//
//   FrontendResult result = runFrontend(survey, options, progress);
//   writeFrontendOutputs(run_folder, result);   // frontend_outputs.h
//
// Frames are decoded on a second thread (frame_prefetcher.h) and tracked in
// order (frame_tracker.h). Afterwards the segments are linked into F, the
// frames' poses are re-expressed through their (bundle-adjusted) keyframes,
// their observations are mapped to the final landmark ids (those of removed
// landmarks dropped), and the tracking losses are collected as frame ranges
// with their reasons.
//
// Errors: std::invalid_argument for invalid options; std::runtime_error when
// the video never initialises, naming the reference frames tried and why
// each failed. Undecodable frames are not errors: they are reported as
// losses (and in `warnings`).

#include <functional>

#include "core/survey/survey.h"
#include "pipelines/frontend/frontend_options.h"
#include "pipelines/frontend/frontend_result.h"

namespace hsmap {

// Called after every frame with (frames done, frames in total, frames per
// second so far), e.g. to draw a progress bar with an ETA.
using FrontendProgress = std::function<void(int done, int total, double frames_per_second)>;

FrontendResult runFrontend(const Survey& survey, const FrontendOptions& options,
                           const FrontendProgress& progress = {});

}  // namespace hsmap
