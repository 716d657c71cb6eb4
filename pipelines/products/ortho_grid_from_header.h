#pragma once
// The ortho grid an ortho-image was written on, read back from its ENVI
// header's map info (used to read a run's ortho-images for the extrinsic
// refinement, extrinsic_refinement.h).

#include "core/io/envi_header.h"
#include "pipelines/products/ortho_grid.h"

namespace hsmap {

// The grid of an ENVI header's map info (UTM, square pixels, reference pixel
// (1, 1)); std::invalid_argument otherwise.
OrthoGrid orthoGridFromHeader(const EnviHeader& header);

}  // namespace hsmap
