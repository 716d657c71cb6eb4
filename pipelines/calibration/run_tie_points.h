#pragma once
// Steps 1-3 of the extrinsic refinement (extrinsic_refinement.h, "Method")
// on a cast of the scan lines (product_casting.h): the RGB ortho-image
// rendered from the mesh on the hyperspectral ortho-image's grid, both
// luminance images (ortho_luminance.h) and their matching into tie points
// (ortho_matching.h).

#include <filesystem>
#include <iosfwd>
#include <vector>

#include "core/geometry/utm_projection.h"
#include "core/io/ply_io.h"
#include "pipelines/calibration/extrinsic_refinement_options.h"
#include "pipelines/calibration/extrinsic_tie_point.h"
#include "pipelines/calibration/ortho_luminance.h"
#include "pipelines/calibration/ortho_matching.h"

namespace hsmap {

// Steps 1-3 on a cast (ORTHO/ortho.*, ancillary.*, made from the lines
// onto `mesh`): the tie points between the two ortho-images, for any solver
// that uses them (this refinement, the joint problem).
struct RunTiePoints {
  std::vector<ExtrinsicTiePoint> tie_points;
  OrthoMatchCounts counts;
  BandCombination combination;  // luma released
  double median_shift_m = 0.0;  // |h - g| over the tie points, on the grid
};
RunTiePoints collectOrthoTiePoints(const std::filesystem::path& ortho_folder, const PlyMesh& mesh,
                                   const UtmProjection& projection,
                                   const ExtrinsicRefinementOptions& options, std::ostream& log);

}  // namespace hsmap
