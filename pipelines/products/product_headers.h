#pragma once
// The ENVI headers of the products stage's rasters, shared by every variant
// (hyperspectral_ortho.h, stacked_products.h), so that their spectral
// description cannot drift apart.
#include <vector>

#include "core/io/envi_header.h"
#include "core/io/envi_reader.h"

namespace hsmap {

// A float32 raster of `rows` x `cols` with the cube's bands: wavelengths in
// nanometres (as the survey loader converted them), the cube's fwhm converted
// likewise, its band names; `data ignore value = NaN` (empty pixels are NaN).
// No map info, no description.
EnviHeader spectralProductHeader(const EnviReader& cube, const std::vector<double>& wavelengths_nm, int rows,
                                 int cols, EnviInterleave interleave);

// The 4-band float32 BIL ancillary raster: scan line, sample, range (m),
// incidence (deg); `data ignore value = NaN`. No map info, no description.
EnviHeader ancillaryProductHeader(int rows, int cols);

}  // namespace hsmap
