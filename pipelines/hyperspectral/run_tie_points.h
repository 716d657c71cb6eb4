#pragma once
// Steps 1-3 of the extrinsic refinement (extrinsic_refinement.h, "Method")
// on a run folder after the products stage: the RGB ortho-image rendered
// from the mesh on the hyperspectral ortho-image's grid, both luminance
// images (ortho_luminance.h) and their matching into tie points
// (ortho_matching.h).

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "core/geometry/utm_projection.h"
#include "pipelines/hyperspectral/extrinsic_refinement_options.h"
#include "pipelines/hyperspectral/extrinsic_tie_point.h"
#include "pipelines/hyperspectral/ortho_luminance.h"
#include "pipelines/hyperspectral/ortho_matching.h"

namespace hsmap {

// Steps 1-3 on a run folder (RUN/hyperspectral/ortho.*, ancillary.*,
// RUN/map/mesh.ply): the tie points between the two ortho-images, for any
// solver that uses them (this refinement, the joint problem).
struct RunTiePoints {
  std::vector<ExtrinsicTiePoint> tie_points;
  OrthoMatchCounts counts;
  BandCombination combination;  // luma released
  double median_shift_m = 0.0;  // |h - g| over the tie points, on the grid
};
RunTiePoints collectTiePointsInRun(const std::filesystem::path& run,
                                   const UtmProjection& projection,
                                   const ExtrinsicRefinementOptions& options, std::ostream& log);

}  // namespace hsmap
