#pragma once
// Steps 2-3 of the extrinsic refinement (extrinsic_refinement.h, "Method"):
// patches of the RGB luminance searched in the hyperspectral luminance by
// normalised cross-correlation on a lattice, each confident match turned
// into a tie point through the ancillary image (the UHI pixel painted at the
// match) and the renderer's points (the mesh point seen there).

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "pipelines/calibration/extrinsic_refinement_options.h"
#include "pipelines/calibration/extrinsic_tie_point.h"
#include "pipelines/products/rgb_ortho.h"

namespace hsmap {

// What the matching did with the lattice's patches.
struct OrthoMatchCounts {
  std::int64_t patches = 0;     // lattice patches
  std::int64_t textured = 0;    // both windows valid, template textured
  std::int64_t matched = 0;     // confident and unambiguous NCC peak
  std::int64_t tie_points = 0;  // of those, with ancillary and a mesh point
  std::int64_t coarse_patches = 0;  // the coarse step's (coarse_ortho_shift.h)
  std::int64_t coarse_matched = 0;
  double coarse_scale = 1.0;  // 0.5: the coarse step's halved windows were used
  std::int64_t shifted = 0;  // textured patches searched around a coarse shift other than 0
};

// Steps 2-3 on two luminance images of one grid: tie points from the
// ancillary image (CV_32FC4: line, sample, range, incidence; NaN empty) and
// the renderer's points. Appends to `tie_points`.
OrthoMatchCounts matchOrthoImages(const cv::Mat& rgb_luma, const cv::Mat& hyper_luma,
                                  const cv::Mat& ancillary, const RgbOrthoRenderer& renderer,
                                  const ExtrinsicRefinementOptions& options,
                                  std::vector<ExtrinsicTiePoint>& tie_points);

}  // namespace hsmap
