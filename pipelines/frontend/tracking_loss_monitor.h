#pragma once
// Tracking losses: which frames have no usable texture, and the ranges of
// frames that were not posed, each with the reason of its first frame.
//
// textureProblem() is the check made on every frame before tracking: a
// black or dim-and-flat frame (grey-level standard deviation below
// min_contrast_dn), or an over-exposed one (more than max_saturated_fraction
// of its pixels at >= 250 DN), cannot be tracked and says so by name. A
// blurred frame passes this check but yields too few corners or tracks, and
// is reported by the tracker ("too few tracked points", "only N inliers").
//
// collectLosses() turns the per-frame outcome into ranges: every maximal run
// of frames that are not posed is one TrackingLoss [first, last] with the
// reason recorded for its first frame that has one. Nothing is left out:
// every unposed frame belongs to exactly one reported range.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pipelines/frontend/frontend_options.h"
#include "pipelines/frontend/frontend_result.h"
#include "pipelines/frontend/image_preprocessor.h"

namespace hsmap {

// "dark (mean 1.2 DN, contrast 0.4 DN)", "over-exposed (63 % saturated)",
// "flat (contrast 1.1 DN)", or nullopt when the frame can be tracked.
std::optional<std::string> textureProblem(const ImageQuality& quality, const FrontendOptions& options);

// `reasons`: frame index -> why it was not posed (first reason kept per frame).
std::vector<TrackingLoss> collectLosses(const std::vector<FrameRecord>& frames,
                                        const std::map<int, std::string>& reasons);

}  // namespace hsmap
